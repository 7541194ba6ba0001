#include "core/strike_line.hpp"

#include <cstdint>

#include <fmt/format.h>

namespace mallet {

std::string format_seconds(Nanos t_ns) {
  const bool negative = t_ns < 0;
  const std::uint64_t magnitude = negative ? 0 - static_cast<std::uint64_t>(t_ns) : static_cast<std::uint64_t>(t_ns);
  return fmt::format("{}{}.{:09}", negative ? "-" : "", magnitude / 1'000'000'000u, magnitude % 1'000'000'000u);
}

std::string strike_line(const Scene& scene, const Impact& i) {
  const Target& t = scene.targets.at(i.target);
  const std::size_t m = static_cast<std::size_t>(i.material);
  const char* material = i.material >= 0 && m < scene.materials.size() ? scene.materials[m].name.c_str() : "?";
  return fmt::format("strike t={} bar={} {} note={} speed={:.3f} m/s material={}", format_seconds(i.t_ns), t.id,
                     t.instrument, t.note, i.speed_m_per_s, material);
}

}  // namespace mallet
