#include "app/bench/bench_input_camera.hpp"
#include "app/bench/bench_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/time.hpp"
#include "input/camera/frame_decode.hpp"
#include "input/camera/led_finder.hpp"
#include "input/camera/led_frame_synth.hpp"

namespace mallet::app::input_bench {

namespace {

namespace cam = input::camera;

// The camera: 640×480 over the kiosk's 0.82 m, 240 Hz, 1 ms exposure; the budget is
// half a millisecond of one core per frame (an eighth of the frame period).
constexpr int kW = 640, kH = 480;
constexpr double kRateHz = 240;
constexpr double kMmPerPx = 820.0 / kW;
constexpr double kBudgetUs = 500;
constexpr int kLoopFrames = 64;  // distinct frames, cycled: a closed circle at 2 m/s

// The LED: σ 1.8 px (its half-maximum 4 px across), 200 levels over a background of 12; a
// dimmer second light (a reflection off the frame) stays put.
cam::SynthScene scene_with(double read_noise, double shot_variance) {
  cam::SynthScene s;
  s.width = kW;
  s.height = kH;
  s.background = 12;
  s.read_noise = read_noise;
  s.shot_variance_per_level = shot_variance;
  s.exposure_s = 0.001;
  return s;
}
constexpr cam::SynthSpot kCameraReflection{560.0, 80.0, 2.0, 70.0, 0.0, 0.0};

struct Frames {
  std::vector<std::vector<std::uint8_t>> grey, yuyv, mjpeg;
  std::vector<std::uint8_t> blank;  // noise only: the LED lost
};

Frames make_frames(std::uint64_t seed) {
  cam::LedFrameSynth synth(static_cast<std::uint32_t>(seed));
  Frames f;
  // A circle at 2 m/s closed in kLoopFrames frames, so cycling the frames is a smooth path.
  const double speed_px = 2000.0 / kMmPerPx;
  const double radius = speed_px * (kLoopFrames / kRateHz) / (2 * std::numbers::pi);
  std::vector<std::uint8_t> luma;
  for (int i = 0; i < kLoopFrames; ++i) {
    const double a = 2 * std::numbers::pi * i / kLoopFrames;
    cam::SynthScene s = scene_with(1.5, 0.1);
    s.spots.push_back({320 + radius * std::cos(a), 240 + radius * std::sin(a), 1.8, 200, -speed_px * std::sin(a),
                       speed_px * std::cos(a)});
    s.spots.push_back(kCameraReflection);
    synth.render(s, luma);
    f.grey.push_back(luma);
    f.yuyv.push_back(*cam::encode_frame(luma, kW, kH, cam::PixelFormat::yuyv));
    f.mjpeg.push_back(*cam::encode_frame(luma, kW, kH, cam::PixelFormat::mjpeg, 0, 85));
  }
  synth.render(scene_with(1.5, 0.1), f.blank);
  return f;
}

struct Stats {
  double median_us = 0, p99_us = 0;
};

Stats stats(const std::vector<double>& us) { return {nearest_rank(us, 0.5), nearest_rank(us, 0.99)}; }

enum class Mode { tracking, acquiring, lost };

// Times `calls` finds (and decodes) over the frames in `bytes`, cycled, in `format`.
struct Timing {
  Stats decode, find, total;
  double found_fraction = 0;
};

Timing time_frames(const std::vector<std::vector<std::uint8_t>>& bytes, cam::PixelFormat format, Mode mode, int calls) {
  cam::LedFinder finder;
  std::vector<std::uint8_t> scratch;
  std::vector<double> dec, fnd, tot;
  dec.reserve(static_cast<std::size_t>(calls));
  fnd.reserve(static_cast<std::size_t>(calls));
  tot.reserve(static_cast<std::size_t>(calls));
  int found = 0;
  for (int i = -kLoopFrames; i < calls; ++i) {  // one lap first: the finder tracking, caches warm
    const std::vector<std::uint8_t>& b = bytes[static_cast<std::size_t>((i + kLoopFrames) % static_cast<int>(bytes.size()))];
    const cam::CameraFrame frame{0, 0, kW, kH, format, 0, b};
    if (mode == Mode::acquiring) finder.reset();
    const Nanos t0 = monotonic_now();
    const auto luma = cam::luma_view(frame, scratch);
    const Nanos t1 = monotonic_now();
    const cam::LedFind f = finder.find(*luma);
    const Nanos t2 = monotonic_now();
    if (i < 0) continue;
    found += f.led ? 1 : 0;
    dec.push_back(1e-3 * static_cast<double>(t1 - t0));
    fnd.push_back(1e-3 * static_cast<double>(t2 - t1));
    tot.push_back(1e-3 * static_cast<double>(t2 - t0));
  }
  return {stats(dec), stats(fnd), stats(tot), static_cast<double>(found) / calls};
}

void print_cost(const Frames& f, int calls) {
  std::printf("\nLED finder cost per %dx%d frame: median / p99 µs over %d calls on one core (budget %.0f µs at %.0f Hz);\n"
              "frames: a σ 1.8 px LED circling at 2 m/s (%d distinct frames, cycled) and a dimmer second light,\n"
              "read noise 1.5 levels + shot noise 0.1 levels² a level; 'lost' frames hold noise only\n",
              kW, kH, calls, kBudgetUs, kRateHz, kLoopFrames);
  // fmt pads by code points (µ is two bytes), printf by bytes.
  fmt::print("| {:<6} | {:<34} | {:<15} | {:<15} | {:<15} | {:<6} | {:<6} |\n", "format", "search", "decode µs", "find µs",
             "total µs", "found", "budget");
  std::printf("|--------|------------------------------------|-----------------|-----------------|-----------------|--------|--------|\n");
  const std::vector<std::vector<std::uint8_t>> blank{f.blank};
  std::vector<std::vector<std::uint8_t>> blank_yuyv{*cam::encode_frame(f.blank, kW, kH, cam::PixelFormat::yuyv)};
  std::vector<std::vector<std::uint8_t>> blank_mjpeg{*cam::encode_frame(f.blank, kW, kH, cam::PixelFormat::mjpeg, 0, 85)};
  struct Row {
    const char* format_name;
    cam::PixelFormat format;
    const std::vector<std::vector<std::uint8_t>>* frames;
    const std::vector<std::vector<std::uint8_t>>* lost;
  };
  const Row rows[] = {{"grey", cam::PixelFormat::grey, &f.grey, &blank},
                      {"yuyv", cam::PixelFormat::yuyv, &f.yuyv, &blank_yuyv},
                      {"mjpeg", cam::PixelFormat::mjpeg, &f.mjpeg, &blank_mjpeg}};
  for (const Row& r : rows)
    for (const Mode m : {Mode::tracking, Mode::acquiring, Mode::lost}) {
      const Timing t = time_frames(m == Mode::lost ? *r.lost : *r.frames, r.format, m, calls);
      const char* what = m == Mode::tracking    ? "steady tracking (ROI 97x97)"
                         : m == Mode::acquiring ? "full frame, LED in view"
                                                : "full frame, lost (nothing in view)";
      auto cell = [](const Stats& s) { return fmt::format("{:6.1f} / {:6.1f}", s.median_us, s.p99_us); };
      std::printf("| %-6s | %-34s | %-15s | %-15s | %-15s | %5.1f%% | %-6s |\n", r.format_name, what, cell(t.decode).c_str(),
                  cell(t.find).c_str(), cell(t.total).c_str(), 100 * t.found_fraction,
                  t.total.p99_us <= kBudgetUs ? "ok" : (t.total.median_us <= kBudgetUs ? "med ok" : "OVER"));
    }
  std::printf("(decode: GREY and YUYV are views in place; the time is the checks. MJPEG: libjpeg-turbo to luma only.)\n");
}

void print_noise(std::uint64_t seed) {
  std::printf("\nCentroid noise on a still LED (σ 1.8 px, 200 levels over 12; 2000 frames at each of 4 subpixel places):\n");
  fmt::print("| {:<34} | {:<9} | {:<9} | {:<9} | {:<9} | {:<13} |\n", "sensor noise assumed", "x RMS px", "y RMS px",
             "x bias px", "y bias px", "RMS mm (x,y)");
  std::printf("|------------------------------------|-----------|-----------|-----------|-----------|---------------|\n");
  struct Noise {
    const char* label;
    double read, shot;
  };
  const Noise models[] = {{"read 1.0 lv, shot 0.05 lv²/lv", 1.0, 0.05},
                          {"read 1.5 lv, shot 0.1 lv²/lv (*)", 1.5, 0.1},
                          {"read 3.0 lv, shot 0.3 lv²/lv", 3.0, 0.3}};
  const double places[][2] = {{320.0, 240.0}, {320.5, 240.5}, {320.25, 240.75}, {320.13, 240.38}};
  cam::LedFrameSynth synth(static_cast<std::uint32_t>(seed + 1));
  std::vector<std::uint8_t> luma;
  for (const Noise& n : models) {
    double sx2 = 0, sy2 = 0, bx = 0, by = 0;
    int count = 0;
    for (const auto& p : places) {
      // A crop around the LED is enough for the noise (the finder sees the same blob) and
      // 25× cheaper to draw than 640×480.
      cam::SynthScene s = scene_with(n.read, n.shot);
      s.width = s.height = 64;
      const double ox = p[0] - 288, oy = p[1] - 208;  // the place in the crop
      s.spots.push_back({ox, oy, 1.8, 200});
      double mx = 0, my = 0, mxx = 0, myy = 0;
      const int frames = 2000;
      cam::LedFinder finder;
      for (int i = 0; i < frames; ++i) {
        synth.render(s, luma);
        const cam::LedFind f = finder.find({64, 64, luma.data(), 64, 1});
        if (!f.led) continue;
        const double ex = f.led->x - ox, ey = f.led->y - oy;
        mx += ex;
        my += ey;
        mxx += ex * ex;
        myy += ey * ey;
        ++count;
      }
      mx /= frames;
      my /= frames;
      sx2 += mxx / frames - mx * mx;
      sy2 += myy / frames - my * my;
      bx = std::max(bx, std::abs(mx));
      by = std::max(by, std::abs(my));
    }
    const double rx = std::sqrt(sx2 / 4), ry = std::sqrt(sy2 / 4);
    fmt::print("| {:<34} | {:9.4f} | {:9.4f} | {:9.4f} | {:9.4f} | {:5.3f}, {:5.3f}  |{}\n", n.label, rx, ry, bx, by,
               rx * kMmPerPx, ry * kMmPerPx, count == 4 * 2000 ? "" : " (LED missed in some frames)");
  }
  std::printf("(*) assumed for the kiosk's camera: read noise σ 1.5 grey levels, shot noise of a sensor at 10 electrons a\n"
              "    level; RMS = the spread around the mean; bias = the worst mean error over the 4 places; %.3f mm a pixel.\n",
              kMmPerPx);
}

}  // namespace

void print_camera_section(std::uint64_t seed, int frames) {
  std::printf("\n## Camera: the LED in V4L2 frames (led_finder, frame_decode)\n");
  const Frames f = make_frames(seed);
  print_cost(f, std::max(frames, 1));
  print_noise(seed);
}

}  // namespace mallet::app::input_bench
