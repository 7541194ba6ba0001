// An answer script (`mallet study --answers FILE`) on arbitrary bytes, read from a file as
// the program does: answers among the protocol's choices with sane response times, or one
// FileError line naming the file.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/study/answer_script.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // The 2AFC answers and the shipped materials' names (a name_material protocol's).
  static const std::vector<std::string> choices = {"1", "2", "wood", "metal", "rubber", "wall_wood", "aluminium"};
  const std::filesystem::path path = mallet::fuzz::scratch().write("answers.txt", mallet::fuzz::text_of(data, size));
  std::vector<mallet::study::ObserverAnswer> answers;
  try {
    answers = mallet::study::read_answer_script(path, choices);
  } catch (const mallet::FileError& e) {
    mallet::fuzz::check_refusal(e, path.string());
    return 0;
  }
  for (const mallet::study::ObserverAnswer& a : answers) {
    if (std::find(choices.begin(), choices.end(), a.answer) == choices.end()) std::abort();
    if (a.response_time < 0 || a.response_time > 3'600'000'000'000) std::abort();
  }
  return 0;
}
