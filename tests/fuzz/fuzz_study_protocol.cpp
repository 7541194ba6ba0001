// A study protocol (config/study/*.toml) on arbitrary text, against the shipped materials
// and the percussion scene's bars: a protocol whose pairs and named stimuli exist, or one
// FileError line naming the file.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "core/config/scene_config.hpp"
#include "core/study/protocol_loader.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const mallet::Scene scene =
      mallet::config::load_scene(mallet::fuzz::source_file("config/scenes/percussion.toml"));
  const std::string name = "fuzz.toml";
  mallet::study::StudyProtocol protocol;
  try {
    protocol = mallet::study::parse_study_protocol(mallet::fuzz::text_of(data, size), name, scene.materials,
                                                   scene.targets.size());
  } catch (const mallet::FileError& e) {
    mallet::fuzz::check_refusal(e, name);
    return 0;
  }
  const auto stimuli = protocol.stimuli.size();
  for (const mallet::study::StimulusPair& p : protocol.pairs)
    if (p.a < 0 || p.b < 0 || static_cast<std::size_t>(p.a) >= stimuli || static_cast<std::size_t>(p.b) >= stimuli)
      std::abort();
  for (int i : protocol.named)
    if (i < 0 || static_cast<std::size_t>(i) >= stimuli) std::abort();
  if (protocol.reference_bar < 0 || static_cast<std::size_t>(protocol.reference_bar) >= scene.targets.size())
    std::abort();
  (void)protocol.answer_choices();
  return 0;
}
