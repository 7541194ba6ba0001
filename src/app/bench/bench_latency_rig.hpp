#pragma once
// `mallet bench latency`'s rig: what every configuration's run shares. The bench's own X
// server and JACK server, the recorder (the ear), the XTest pointer (the hand), the
// framebuffer's reader and its watch on the bars (the eye); the still scene the kiosk plays
// and the two bars the hand strikes, with the window's pixels mapped to world metres; and
// the whole run's bound.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/bench/bench_kiosk_child.hpp"
#include "app/bench/bench_latency_jack.hpp"
#include "app/bench/bench_latency_x11.hpp"
#include "core/scene.hpp"
#include "core/time.hpp"

namespace mallet::app::latency {

inline constexpr int kWidth = 960, kHeight = 540;  //!< the screen, and the kiosk's window on all of it
inline constexpr int kRate = 48000, kPeriod = 128;  //!< the JACK server's
inline constexpr int kPictureTolerancePx = 1;

//! The whole run's bound, and every wait's check for a signal.
struct Deadline {
  Nanos end = 0;
  //! Throws "bench latency: stopped by signal N" or "… took longer than its bound".
  void check() const;
};

//! The shipped percussion scene with no visual vibration: a copy of the scene and of its
//! materials file with every material's visual amplitude_s set to 0 (the actuator and the
//! acoustic parameters as shipped). The bounce lifts the head a few mm right after the
//! contact, which would delay the picture's "mallet at the bar"; without it, the first
//! frame that shows the head at the bar is the frame where the bounce starts.
std::filesystem::path still_scene(const std::filesystem::path& dir);

//! A bar the hand strikes, in world metres and window pixels.
struct Bar {
  int target = 0;
  std::string name;        //!< "glockenspiel bar 4 (metal)"
  double x_m = 0;          //!< the bar's middle
  double contact_y_m = 0;  //!< top + mallet radius: the sphere's centre at contact
  int x_px = 0;            //!< the middle, window pixels
  PixelBox strip;          //!< where the picture watch looks, screen pixels
};

//! The kiosk's window pixels ↔ world metres: the window is the whole screen, and the
//! kiosk maps a cursor at (px, py) to screen_to_world(px / width, py / height).
struct Mapping {
  const Scene* scene = nullptr;
  double y_of_row(int row) const { return scene->screen_to_world.map(0.5, static_cast<double>(row) / kHeight).y; }
  double row_of_y(double y) const { return scene->screen_to_world.unmap({0.0, y}).y * kHeight; }
  double col_of_x(double x) const { return scene->screen_to_world.unmap({x, 0.0}).x * kWidth; }
};

//! A metal bar and a wood bar, each its instrument's middle one (in that order).
std::vector<Bar> choose_bars(const Scene& scene, const Mapping& map);

//! Everything the runs share: the servers, the recorder, the hand, the eye.
struct Rig {
  KioskFolders folders{"mallet-bench-latency"};  //!< the kiosk's runtime and state folders, and ours
  std::filesystem::path scene_file;
  Scene scene;
  Mapping map;
  std::vector<Bar> bars;
  std::unique_ptr<VirtualDisplay> x;
  std::unique_ptr<JackServer> jack;
  std::unique_ptr<JackRecorder> recorder;
  std::unique_ptr<FakePointer> hand;
  std::unique_ptr<ScreenReader> eye;
  std::unique_ptr<PictureWatch> watch;
  int rest_row[2] = {-1, -1};  //!< where the head rests on each bar (a mouse run's warm-up)
};

}  // namespace mallet::app::latency
