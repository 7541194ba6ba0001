// The renderer part of `mallet bench report`: ms per frame against the image error (RMS
// against a 2×2-supersampled reference filtered in linear light) for antialiasing, the
// shadow and the render scale, with the clear + read-back floor of the same run; and what
// skipping work the frame does not need saves.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "app/bench_report.hpp"
#include "app/render_setup.hpp"
#include "core/quality.hpp"
#include "render/vk_error.hpp"

namespace mallet::app {
namespace {

using Clock = std::chrono::steady_clock;

double median_frame_ms(HeadlessRenderer& r, const render::FrameState& state, int frames) {
  r.draw(state);  // warm-up
  std::vector<double> ms;
  for (int i = 0; i < frames; ++i) {
    const auto t0 = Clock::now();
    r.draw(state);
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  std::nth_element(ms.begin(), ms.begin() + static_cast<long>(ms.size() / 2), ms.end());
  return ms[ms.size() / 2];
}

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

VkSampleCountFlagBits samples_of(int n) {
  return n == 8 ? VK_SAMPLE_COUNT_8_BIT : n == 4 ? VK_SAMPLE_COUNT_4_BIT : n == 2 ? VK_SAMPLE_COUNT_2_BIT
                                                                                : VK_SAMPLE_COUNT_1_BIT;
}

}  // namespace

void measure_render_trades(const Scene& scene, const ReportOptions& o, ReportSections& out) {
  if (scene.targets.empty()) return;
  const VkExtent2D size = o.quick ? VkExtent2D{320, 180} : VkExtent2D{1920, 1080};
  const int frames = o.quick ? 3 : 60;
  const Target& a = scene.targets.at(std::min<std::size_t>(3, scene.targets.size() - 1));
  render::FrameState state;
  state.mallet_centre = {a.x_max + 0.004, 0.035};  // just above a bar, the shadow on two bars
  const auto cache = std::filesystem::temp_directory_path() / "mallet-bench-report-cache";
  auto make = [&](int msaa, bool shadow, VkExtent2D extent) {
    HeadlessOptions h;
    h.size = extent;
    h.settings.samples = samples_of(msaa);
    h.settings.shadow = shadow;
    h.device = o.device;
    h.validation = render::Validation::off;
    h.cache_dir = cache;
    return std::make_unique<HeadlessRenderer>(scene, h);
  };
  std::unique_ptr<HeadlessRenderer> base;
  try {
    base = make(1, true, size);
  } catch (const std::exception& e) {
    out.skipped.push_back(std::string("renderer: ") + e.what());
    return;
  }
  const std::string device = base->context().device_name();
  const int auto_samples = static_cast<int>(render::recommended_samples(base->context()));
  const render::Image reference = downsample_linear_light(make(1, true, {size.width * 2, size.height * 2})->render(state), 2);

  render::FrameState floor_state = state;
  floor_state.draw_instruments = false;
  floor_state.draw_mallet = false;
  const double floor_ms = median_frame_ms(*base, floor_state, frames);

  const char* size_text = o.quick ? "320×180" : "1920×1080";
  TradeTable t{"render", std::string("Renderer at ") + size_text + " on " + device, "ms per frame (incl. read-back)",
               "RMS error vs 2×2 supersampled, 1/255", false, {}, ""};
  auto preset_of = [&](int msaa, bool shadow) {
    std::string p;
    for (Quality q : {Quality::fast, Quality::balanced, Quality::exact}) {
      const QualityKnobs k = quality_knobs(q);
      const int s = k.msaa == "auto" ? auto_samples : std::stoi(k.msaa);
      if (s == msaa && k.shadow == shadow) p += std::string(p.empty() ? "" : " ") + to_string(q);
    }
    return p;
  };
  for (int msaa : {1, 2, 4, 8})
    for (bool shadow : {false, true}) {
      if (msaa > 1 && !shadow && preset_of(msaa, shadow).empty()) continue;
      std::unique_ptr<HeadlessRenderer> r;
      try {
        r = make(msaa, shadow, size);
      } catch (const render::RenderError&) {
        continue;  // not offered by this device
      }
      const double ms = median_frame_ms(*r, state, frames);
      const render::ImageDiff d = render::compare_images(r->read_back(), reference, 3);
      char label[64];
      std::snprintf(label, sizeof label, "%s, %s", msaa == 1 ? "no AA" : (std::to_string(msaa) + "x MSAA").c_str(),
                    shadow ? "shadow" : "no shadow");
      char note[64];
      std::snprintf(note, sizeof note, "%.1f× floor", ms / floor_ms);
      t.points.push_back({label, ms, d.rms, preset_of(msaa, shadow), note});
    }
  {
    auto r = make(1, false, {size.width / 2, size.height / 2});
    const double ms = median_frame_ms(*r, state, frames);
    const render::ImageDiff d = render::compare_images(upscale2(r->read_back()), reference, 3);
    char note[64];
    std::snprintf(note, sizeof note, "%.1f× floor; bilinear upscale", ms / floor_ms);
    t.points.push_back({"half scale, no AA, no shadow", ms, d.rms, "", note});
  }
  char note[256];
  std::snprintf(note, sizeof note,
                "Floor (clear + read-back, same size, same run): %.2f ms. `auto` antialiasing on this device = %dx.",
                floor_ms, auto_samples);
  t.note = note;
  for (const TradePoint& p : t.points)
    if (p.presets.find("balanced") != std::string::npos) out.frame_ms_balanced = p.time;
  out.trades.push_back(t);

  // Model only what the frame needs: the shadow with no caster in view.
  TextTable savings{"Work the frame does not need (" + std::string(size_text) + ")", {"case", "ms per frame", "note"}, {}, ""};
  render::FrameState no_caster = state;
  no_caster.draw_mallet = false;
  const double with_shadow = median_frame_ms(*base, no_caster, frames);
  auto plain = make(1, false, size);
  const double without = median_frame_ms(*plain, no_caster, frames);
  char b1[32], b2[32];
  std::snprintf(b1, sizeof b1, "%.2f", with_shadow);
  std::snprintf(b2, sizeof b2, "%.2f", without);
  savings.rows.push_back({"mallet out of view, shadow enabled", b1, "the analytic shadow is evaluated per fragment of the bars"});
  savings.rows.push_back({"mallet out of view, shadow disabled", b2, "what skipping it when no caster is in view would save"});
  savings.note = "The shadow is analytic (no shadow-map pass) and there is no full-screen pass besides the one "
                 "scene pass and the overlay, so the saving is small; see the report's notes.";
  out.tables.push_back(savings);
  std::filesystem::remove_all(cache);
}

}  // namespace mallet::app
