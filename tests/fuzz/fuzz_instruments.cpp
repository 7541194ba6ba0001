// The acoustic presets (config/instruments.toml) on arbitrary text: one or more presets of
// 1..kMaxModalModes modes, the first the fundamental, or one FileError line naming the file.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "core/config/instruments_config.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string name = "fuzz.toml";
  std::vector<mallet::ModalPreset> presets;
  try {
    presets = mallet::config::parse_instruments(mallet::fuzz::text_of(data, size), name);
  } catch (const mallet::FileError& e) {
    mallet::fuzz::check_refusal(e, name);
    return 0;
  }
  if (presets.empty()) std::abort();
  for (const mallet::ModalPreset& p : presets) {
    if (p.modes.empty() || p.modes.size() > static_cast<std::size_t>(mallet::kMaxModalModes)) std::abort();
    if (p.modes.front().ratio != 1.0) std::abort();
    if (!(p.loudness >= 0 && p.loudness <= 1) || !(p.brightness >= 0 && p.brightness <= 1)) std::abort();
  }
  return 0;
}
