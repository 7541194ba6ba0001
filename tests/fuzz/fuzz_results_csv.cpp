// The study's results CSV on arbitrary bytes, read from a file as a resumed study or
// `mallet study summary` does: complete rows (an incomplete last line only warned about),
// or one FileError line naming the file; the summary of what was read never fails.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/study/results_csv.hpp"
#include "core/study/study_summary.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = mallet::fuzz::scratch().write("results.csv", mallet::fuzz::text_of(data, size));
  const std::string name = path.string();
  mallet::study::ResultsFile file;
  try {
    file = mallet::study::read_results(path);
  } catch (const mallet::FileError& e) {
    mallet::fuzz::check_refusal(e, name);
    return 0;
  }
  if (!file.exists || file.complete_bytes > size || file.rows.size() != file.lines.size()) std::abort();
  if (!file.rows.empty() && !file.has_header) std::abort();
  for (const std::string& w : file.warnings)
    if (w.substr(0, name.size()) != name || w.find_first_of("\n\r") != std::string::npos) std::abort();
  for (const mallet::study::ResultRow& r : file.rows)
    if (r.trial < 1) std::abort();
  (void)mallet::study::format_summary(mallet::study::summarize(file.rows));
  if (!file.rows.empty())
    (void)mallet::study::format_summary(mallet::study::summarize(file.rows, file.rows.front().participant));
  return 0;
}
