#pragma once
// A material as both papers use it: one Eq. 1 triple for what the eye sees (the
// cursor's visual vibration) and one for what the hand feels (the actuator).
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/vibration.hpp"

namespace mallet {

struct Material {
  //! Warm white, for a material that names no glow.
  static constexpr std::array<double, 3> kDefaultGlowSrgb{1.0, 0.85, 0.6};

  std::string name;          //!< key in config/materials.toml, e.g. "wood"
  std::string display_name;  //!< what a visitor or an operator reads, e.g. "Wood"
  VibrationParams visual;    //!< A in seconds: A·v metres of cursor displacement
  VibrationParams actuator;  //!< A as a ratio of the actuator's full scale per m/s
  std::string source;        //!< where the numbers come from (Table 1, derived, ...)
  //! The hue a bar of this material glows with when struck or hovered over (sRGB, 0..1, as
  //! a designer picks it; the renderer sets its strength): config key `glow_srgb`.
  std::array<double, 3> glow_srgb = kDefaultGlowSrgb;
};

class MaterialLibrary {
 public:
  MaterialLibrary() = default;
  explicit MaterialLibrary(std::vector<Material> materials) : materials_(std::move(materials)) {}

  const Material* find(std::string_view name) const;
  const std::vector<Material>& all() const { return materials_; }
  std::string names() const;  //!< "wood, metal, ..." for error messages

 private:
  std::vector<Material> materials_;
};

}  // namespace mallet
