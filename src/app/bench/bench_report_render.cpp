// The renderer part of `mallet bench report`: ms per frame against the image error (RMS
// against a 2×2-supersampled reference filtered in linear light) for antialiasing, the
// shadow and the render scale, with the clear + read-back floor of the same run; and what
// skipping work the frame does not need saves.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app/bench/bench_kiosk_child.hpp"
#include "app/bench/bench_kiosk_cpu.hpp"
#include "app/bench/bench_report.hpp"
#include "render/render_setup.hpp"
#include "core/quality.hpp"
#include "render/vk_error.hpp"

namespace mallet::app {
namespace {

using Clock = std::chrono::steady_clock;

//! Bilinear upscale by 2 (a half-scale frame shown full size, as a scaler would).
render::Image upscale2(const render::Image& in) {
  render::Image out(in.width * 2, in.height * 2);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const double sx = std::clamp((x + 0.5) / 2.0 - 0.5, 0.0, in.width - 1.0);
      const double sy = std::clamp((y + 0.5) / 2.0 - 0.5, 0.0, in.height - 1.0);
      const int x0 = static_cast<int>(sx), y0 = static_cast<int>(sy);
      const int x1 = std::min(x0 + 1, in.width - 1), y1 = std::min(y0 + 1, in.height - 1);
      const double fx = sx - x0, fy = sy - y0;
      for (int c = 0; c < 4; ++c) {
        const double v = (1 - fy) * ((1 - fx) * in.at(x0, y0)[c] + fx * in.at(x1, y0)[c]) +
                         fy * ((1 - fx) * in.at(x0, y1)[c] + fx * in.at(x1, y1)[c]);
        out.at(x, y)[c] = static_cast<std::uint8_t>(std::lround(v));
      }
    }
  return out;
}

}  // namespace

void measure_render_trades(const Scene& scene, const ReportOptions& o, ReportSections& out) {
  if (scene.targets.empty()) return;
  const VkExtent2D size = o.quick ? VkExtent2D{320, 180} : VkExtent2D{1920, 1080};
  const int frames = o.quick ? 3 : 10;
  const Target& a = scene.targets.at(std::min<std::size_t>(3, scene.targets.size() - 1));
  render::FrameState state;
  state.mallet_centre = {a.x_max + 0.004, 0.035};  // just above a bar, the shadow on two bars
  const latency::TempDir scratch("mallet-bench-report");  // this run's own, removed at the end
  const auto cache = scratch.path() / "pipeline-cache";
  // `background_msaa` 0: the frames' own; `cached` false: the whole scene every frame.
  auto make = [&](int msaa, bool shadow, VkExtent2D extent, int background_msaa = 0, bool cached = true) {
    render::HeadlessOptions h;
    h.size = extent;
    h.settings.samples = samples_of(msaa);
    h.settings.background_samples = samples_of(background_msaa == 0 ? msaa : background_msaa);
    h.settings.background_cache = cached;
    h.settings.shadow = shadow;
    h.device = o.device;
    h.validation = render::Validation::off;
    h.cache_dir = cache;
    return std::make_unique<render::HeadlessRenderer>(scene, h);
  };
  std::unique_ptr<render::HeadlessRenderer> base;
  try {
    base = make(1, true, size);
  } catch (const std::exception& e) {
    out.skipped.push_back(std::string("renderer: ") + e.what());
    return;
  }
  const std::string device = base->context().device_name();
  render::RenderSettings auto_settings;
  render::use_recommended_antialiasing(base->context(), auto_settings);
  const int auto_samples = static_cast<int>(auto_settings.samples);
  const int auto_background = static_cast<int>(auto_settings.background_samples);
  const render::Image reference = downsample_linear_light(make(1, true, {size.width * 2, size.height * 2})->render(state), 2);

  const char* size_text = o.quick ? "320×180" : "1920×1080";
  // The presets whose knobs give these samples (frames, background) and shadow.
  auto preset_of = [&](int msaa, bool shadow, int background_msaa = 0) {
    if (background_msaa == 0) background_msaa = msaa;
    if (msaa > 1) background_msaa = msaa;  // the background then has the frames' samples
    std::string p;
    for (const auto& [q, quality] : kQualityNames) {
      const QualityKnobs k = quality_knobs(q);
      const int s = k.msaa == "auto" ? auto_samples : std::stoi(k.msaa);
      const int b = k.msaa == "auto" ? (s > 1 ? s : auto_background) : s;
      if (s == msaa && b == background_msaa && k.shadow == shadow) p += std::string(p.empty() ? "" : " ") + quality;
    }
    return p;
  };

  // Every case is timed in turn, round after round, so that a load that comes and goes on a
  // shared machine falls on all of them alike.
  struct Case {
    std::string label;
    std::unique_ptr<render::HeadlessRenderer> r;
    render::FrameState state;
    bool trade = true, half = false;
    std::string presets;
    std::vector<double> ms;
  };
  std::vector<Case> cases;
  render::FrameState floor_state = state;
  floor_state.draw_instruments = false;
  floor_state.draw_mallet = false;
  render::FrameState no_caster = state;
  no_caster.draw_mallet = false;
  cases.push_back({"floor", make(1, false, size), floor_state, false, false, "", {}});
  for (int msaa : {1, 2, 4, 8})
    for (bool shadow : {false, true}) {
      if (msaa > 1 && !shadow && preset_of(msaa, shadow).empty()) continue;
      try {
        const std::string label = fmt::format("{}, {}", msaa == 1 ? "no AA" : (std::to_string(msaa) + "x MSAA").c_str(),
                                              shadow ? "shadow" : "no shadow");
        cases.push_back({label, make(msaa, shadow, size), state, true, false, preset_of(msaa, shadow), {}});
      } catch (const render::RenderError&) {
        // not offered by this device
      }
    }
  for (int background_msaa : {2, 4, 8}) {
    if (!render::supports_samples(base->context(), samples_of(background_msaa))) continue;
    cases.push_back({"no AA, background " + std::to_string(background_msaa) + "x MSAA, shadow",
                     make(1, true, size, background_msaa), state, true, false, preset_of(1, true, background_msaa),
                     {}});
  }
  cases.push_back({"no AA, shadow, whole scene every frame (no cached background)", make(1, true, size, 0, false),
                   state, true, false, "", {}});
  cases.push_back({"half scale, no AA, no shadow", make(1, false, {size.width / 2, size.height / 2}), state, true, true, "", {}});
  cases.push_back({"mallet out of view, shadow enabled", make(1, true, size), no_caster, false, false, "", {}});
  cases.push_back({"mallet out of view, shadow disabled", make(1, false, size), no_caster, false, false, "", {}});
  const int rounds = o.quick ? 1 : 6;
  for (Case& c : cases) c.r->draw(c.state);  // warm-up
  for (int round = 0; round < rounds; ++round)
    for (Case& c : cases)
      for (int i = 0; i < frames; ++i) {
        const auto t0 = Clock::now();
        c.r->draw(c.state);
        c.ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
      }
  auto median_of = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const double floor_ms = median_of(cases.front().ms);

  TradeTable t{"render", std::string("Renderer at ") + size_text + " on " + device, "ms per frame (incl. read-back)",
               "RMS error vs 2×2 supersampled, 1/255", false, {}, ""};
  TextTable savings{"Work the frame does not need (" + std::string(size_text) + ")", {"case", "ms per frame", "× floor"}, {}, ""};
  for (Case& c : cases) {
    const double ms = median_of(c.ms);
    const std::string x = fmt::format("{:.1f}× floor", ms / floor_ms);
    if (c.trade) {
      c.r->render(c.state);
      const render::Image image = c.half ? upscale2(c.r->read_back()) : c.r->read_back();
      const render::ImageDiff d = render::compare_images(image, reference, 3);
      t.points.push_back({c.label, ms, d.rms, c.presets, std::string(x) + (c.half ? "; bilinear upscale" : "")});
    } else if (&c != &cases.front()) {
      const std::string b = fmt::format("{:.2f}", ms);
      savings.rows.push_back({c.label, b, x});
    }
  }
  const std::string note =
      fmt::format("Floor (clear + read-back, same size, same run): {:.2f} ms. `auto` antialiasing on this device = {}x "
                  "per frame, {}x for the cached background of the instruments. "
                  "{} rounds × {} frames per case, the cases interleaved.", floor_ms, auto_samples,
                  auto_samples > 1 ? auto_samples : auto_background, rounds, frames);
  t.note = note;
  for (const TradePoint& p : t.points)
    if (p.presets.find("balanced") != std::string::npos) out.frame_ms_balanced = p.time;
  out.trades.push_back(t);
  savings.note = "The static instruments are drawn once per image size into a cached background; a frame copies it, "
                 "redraws the instruments only where the mallet's shadow can fall, and draws the mallet. The shadow is "
                 "analytic (no shadow-map pass); with its caster out of view it costs nothing.";
  out.tables.push_back(savings);
}

void measure_kiosk_cpu_part(const Scene&, const ReportOptions& o, ReportSections& out) {
  if (o.quick) {
    out.skipped.push_back("the kiosk's CPU: not measured in a quick report (it runs the kiosk for 40 s)");
    return;
  }
  std::vector<KioskCpuRow> rows;
  try {
    rows = measure_kiosk_cpu(1920, 1080, 10.0, o.device);
  } catch (const std::runtime_error& e) {
    out.skipped.push_back(std::string("the kiosk's CPU: ") + e.what());
    return;
  }
  out.tables.push_back(kiosk_cpu_table(rows, 1920, 1080));
}

}  // namespace mallet::app
