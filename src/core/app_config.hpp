#pragma once
// The kiosk's settings (config/mallet.toml). The defaults here are the shipped file's
// values; a test keeps the two equal.
#include "core/mallet.hpp"
#include "core/visual_vibration.hpp"

namespace mallet {

struct ActuatorConfig {
  double gain = 0.2;             //!< the paper's amplifier knob: output = gain·A·v·e^(−Bt)·sin
  double soft_clip_knee = 0.9;   //!< identity below, tanh shoulder to full scale above
};

//! Which output channel carries what. Both on one channel = mono mix (no actuator fitted).
struct AudioRouting {
  int channels = 2;
  int acoustic = 0;
  int actuator = 1;
};

struct AudioConfig {
  int sample_rate_hz = 48000;
  AudioRouting routing;
};

struct AppConfig {
  ContactConfig contact;
  BounceMode bounce = BounceMode::signed_eq1;
  ActuatorConfig actuator;
  AudioConfig audio;
};

}  // namespace mallet
