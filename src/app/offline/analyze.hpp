#pragma once
// `mallet analyze`: fits Eq. 1 to what `mallet simulate` wrote, impact by impact, so
// that the stimuli can be compared with the material table (Table 1) rather than
// trusted.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/damped_sine_fit.hpp"
#include "core/time.hpp"

namespace mallet::app {

struct ImpactAnalysis {
  Nanos t_ns = 0;
  std::string material;
  double velocity = 0;
  DampedSineFit visual;    //!< fitted to cursor.csv's offset column
  DampedSineFit actuator;  //!< fitted to the actuator channel of audio.wav
};

//! Reads DIR/events.csv, DIR/cursor.csv and channel `actuator_channel` of DIR/audio.wav.
std::vector<ImpactAnalysis> analyze_simulation(const std::filesystem::path& dir, int actuator_channel);

}  // namespace mallet::app
