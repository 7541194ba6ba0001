#include "core/strike_line.hpp"

#include <cinttypes>
#include <cstdint>
#include <cstdio>

namespace mallet {

std::string format_seconds(Nanos t_ns) {
  const bool negative = t_ns < 0;
  const std::uint64_t magnitude = negative ? 0 - static_cast<std::uint64_t>(t_ns) : static_cast<std::uint64_t>(t_ns);
  char buf[48];
  std::snprintf(buf, sizeof buf, "%s%" PRIu64 ".%09" PRIu64, negative ? "-" : "",
                magnitude / 1'000'000'000u, magnitude % 1'000'000'000u);
  return buf;
}

std::string strike_line(const Scene& scene, const Impact& i) {
  const Target& t = scene.targets.at(i.target);
  char buf[224];
  const std::size_t m = static_cast<std::size_t>(i.material);
  const char* material = i.material >= 0 && m < scene.materials.size() ? scene.materials[m].name.c_str() : "?";
  std::snprintf(buf, sizeof buf, "strike t=%s bar=%d %s note=%d speed=%.3f m/s material=%s",
                format_seconds(i.t_ns).c_str(), t.id, t.instrument.c_str(), t.note, i.speed_m_per_s, material);
  return buf;
}

}  // namespace mallet
