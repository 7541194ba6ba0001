#pragma once
// What the windowed kiosk costs the CPU, as a fanless kiosk PC pays it: the real kiosk,
// fullscreen on its own virtual X server (Xvfb) at the given size, its sound on a JACK
// server of the bench's own, measured from /proc (user + system time of all its threads)
// over a stretch of the attract mode with nobody there, over a stretch of play (the
// bench's XTest pointer sweeping over the bars, dipping into them) and over one still (the
// pointer at rest above the bars: no frame changes, none is drawn), with the frame budget
// ([render] max_fps, the refresh) and without it (`mallet run --no-frame-cap`). Used by
// `mallet bench render` and the bench report.
#include <string>
#include <vector>

#include "app/bench/bench_report.hpp"

namespace mallet::app {

struct KioskCpuRow {
  bool capped = true;
  std::string phase;          //!< "attract", "play" or "still"
  double cpu_percent = 0;     //!< of one core, the kiosk's process
  double x_server_percent = 0;  //!< of one core, the virtual X server's (not on a real kiosk)
  double fps = 0;             //!< frames a second, from the kiosk's metrics file
};

//! Runs the kiosk twice (capped, then not), each phase for `seconds`. Throws with the
//! reason when Xvfb or jackd is missing or the kiosk does not come up.
std::vector<KioskCpuRow> measure_kiosk_cpu(int width, int height, double seconds, const std::string& device);

//! The rows as `bench render` prints them and the bench report writes them.
TextTable kiosk_cpu_table(const std::vector<KioskCpuRow>& rows, int width, int height);

}  // namespace mallet::app
