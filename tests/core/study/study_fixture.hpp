#pragma once
// A small 2AFC protocol over the shipped scene's materials, for the study tests.
#include <string>

#include "core/study/protocol_loader.hpp"
#include "test_paths.hpp"

namespace mallet::test {

inline const char* kTwoAfcProtocol = R"(
name = "t"
task = "2afc_harder"
conditions = ["visual_only", "tactile_only", "both", "none"]
repetitions = 4
seed = 42
[[stimulus]]
name = "wood"
material = "wood"
[[stimulus]]
name = "wood_B110"
material = "wood"
decay_scale = 1.1
[[stimulus]]
name = "metal"
material = "metal"
[[pair]]
a = "wood"
b = "wood_B110"
[[pair]]
a = "metal"
b = "wood"
)";

inline study::StudyProtocol parse_protocol(const std::string& text, const std::string& name = "p.toml") {
  return study::parse_study_protocol(text, name, percussion().materials, percussion().targets.size());
}

}  // namespace mallet::test
