#include "core/quality.hpp"

namespace mallet {

QualityKnobs quality_knobs(Quality q) {
  QualityKnobs k;  // balanced: the shipped defaults
  const AppConfig defaults;
  k.msaa = defaults.render.msaa;
  k.shadow = defaults.render.shadow;
  k.present_mode = defaults.render.present_mode;
  k.frames_per_buffer = defaults.audio.frames_per_buffer;
  k.schedule_ahead_ms = defaults.audio.schedule_ahead_ms;
  k.max_modes = defaults.audio.max_modes;
  k.pointer = defaults.pointer;
  k.predict_horizon_ms = defaults.timing.predict.horizon_ms;
  switch (q) {
    case Quality::fast:
      k.msaa = "1";
      break;
    case Quality::balanced:
      break;
    case Quality::exact:
      k.msaa = "4";
      k.schedule_ahead_ms = 12.0;
      k.predict_horizon_ms = 0;  // the constant 12 ms covers the camera: every speed from the samples
      break;
  }
  return k;
}

void apply_quality(Quality q, AppConfig& config) {
  const QualityKnobs k = quality_knobs(q);
  config.quality = q;
  config.render.msaa = k.msaa;
  config.render.shadow = k.shadow;
  config.render.present_mode = k.present_mode;
  config.audio.frames_per_buffer = k.frames_per_buffer;
  config.audio.schedule_ahead_ms = k.schedule_ahead_ms;
  config.audio.max_modes = k.max_modes;
  config.pointer = k.pointer;
  config.timing.predict.horizon_ms = k.predict_horizon_ms;
}

std::optional<Quality> parse_quality(std::string_view text) { return value_named(kQualityNames, text); }

const char* to_string(CueAlign a) { return name_in(kCueAlignNames, a); }

const char* to_string(Quality q) { return name_in(kQualityNames, q); }

}  // namespace mallet
