#pragma once
// A strike in words, as the logs and the CSVs write it: the kiosk's journal line of each
// strike, and seconds with every nanosecond digit (simulate's events.csv, the replay's origin).
#include <string>

#include "core/impact.hpp"
#include "core/scene.hpp"
#include "core/time.hpp"

namespace mallet {

//! "12.000000042": seconds with all nine nanosecond digits.
std::string format_seconds(Nanos t_ns);

//! "strike t=12.345678901 bar=3 xylophone note=77 speed=1.200 m/s material=wood"
std::string strike_line(const Scene& scene, const Impact& impact);

}  // namespace mallet
