// The materials file (config/materials.toml) on arbitrary text: a library of at least one
// material with usable triples, or one FileError line naming the file.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "core/config/materials_config.hpp"
#include "fuzz_support.hpp"

namespace {
bool usable(const mallet::VibrationParams& p) {
  return std::isfinite(p.amplitude) && p.amplitude >= 0 && std::isfinite(p.decay_per_s) && p.decay_per_s >= 0 &&
         std::isfinite(p.freq_hz) && p.freq_hz > 0;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string name = "fuzz.toml";
  mallet::MaterialLibrary library;
  try {
    library = mallet::config::parse_materials(mallet::fuzz::text_of(data, size), name);
  } catch (const mallet::FileError& e) {
    mallet::fuzz::check_refusal(e, name);
    return 0;
  }
  if (library.all().empty()) std::abort();
  for (const mallet::Material& m : library.all()) {
    if (!usable(m.visual) || !usable(m.actuator)) std::abort();
    if (library.find(m.name) == nullptr) std::abort();
  }
  (void)library.names();
  return 0;
}
