#pragma once
// `mallet bench soak`: the real windowed kiosk left to run for hours, with a scripted
// visitor, watched from outside. The kiosk is a child process on the bench's own virtual X
// server (Xvfb; lavapipe draws) and JACK server (the dummy driver: paced like a sound card;
// ALSA's file plugin is not, see bench_latency_jack.hpp). A visitor strikes a bar every few
// seconds with the X pointer (XTest), soft and hard, bar after bar, for two minutes, then
// leaves for one: the attract mode's ghost player takes over. Every sample period (a minute)
// the bench writes a row of soak.csv: the kiosk's resident memory, open descriptors and
// threads (/proc), its Vulkan device memory and frame times (its own metrics file), and
// every strike it logged, checked against the recorded audio: a strike whose onset is not
// found on the actuator or the note channel is lost. At the end: soak.svg and the growth per
// hour of each figure.
#include <filesystem>
#include <string>

namespace CLI {
class App;
}

namespace mallet::app::soak {

struct SoakOptions {
  double hours = 0;
  std::filesystem::path out = ".";
  double strike_every_s = 3.0;  //!< between two strokes of the scripted visitor
  double sample_every_s = 60.0;
  std::string device;  //!< the kiosk's Vulkan device (substring); empty = its own choice
};

//! Runs the soak; writes OUT/soak.csv, OUT/soak.svg and OUT/kiosk.log, prints the growth per
//! hour. Returns 0 when no strike was lost and the kiosk ran to the end, 1 otherwise; throws
//! when the rig cannot be set up. Ctrl+C ends it early with what was gathered so far.
int run_bench_soak(const SoakOptions& options);

}  // namespace mallet::app::soak
