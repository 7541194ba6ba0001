// The settings file (mallet.toml) on arbitrary text: it either gives a configuration or
// throws one FileError line naming the file; nothing else escapes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "core/config/app_config_loader.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string name = "fuzz.toml";
  mallet::AppConfig config;
  try {
    config = mallet::config::parse_app_config(mallet::fuzz::text_of(data, size), name);
  } catch (const mallet::FileError& e) {
    mallet::fuzz::check_refusal(e, name);
    return 0;
  }
  // What the loader promises the audio route: its channels exist.
  const auto& routing = config.audio.routing;
  if (routing.acoustic < 0 || routing.acoustic >= routing.channels) std::abort();
  if (routing.actuator < 0 || routing.actuator >= routing.channels) std::abort();
  if (config.audio.sample_rate_hz < 8000 || config.audio.sample_rate_hz > 384000) std::abort();
  if (config.audio.frames_per_buffer < 16 || config.audio.frames_per_buffer > 8192) std::abort();
  return 0;
}
