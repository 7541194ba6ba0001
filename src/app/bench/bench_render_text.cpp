#include "app/bench/bench_render_text.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "core/catalogue_file.hpp"
#include "core/config/scene_config.hpp"
#include "core/data_paths.hpp"
#include "core/visitor_catalogues.hpp"
#include "core/visitor_language.hpp"
#include "render/overlay.hpp"
#include "render/render_setup.hpp"
#include "render/text_wrap.hpp"

namespace mallet::app {
namespace {

using Clock = std::chrono::steady_clock;

double elapsed_ms(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double median_ms(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

//! A page of every text of the catalogue (mallet.pot's, in the language in use), wrapped into a
//! panel as large as the operator page's, at its 3/4 size: as much text as a screen shows.
void draw_page(render::Overlay& o, const std::vector<std::string>& msgids, float width, float height) {
  const render::FontAtlas& font = o.atlas();
  const float scale = 0.75f, em = font.pixel_height() * scale, line = em * 1.35f;
  const float x = width * 0.05f, w = width * 0.9f;
  o.fill_rect(x, height * 0.05f, w, height * 0.9f, {0.05f, 0.05f, 0.07f, 0.88f});
  if (msgids.empty()) return;  // the panel alone
  const bool rtl = render::right_to_left(visitor_language());
  float y = height * 0.05f + line;
  for (const std::string& id : msgids)
    for (const std::string& row : render::wrap_text(font, tr(id.c_str()), (w - 2 * em) / scale)) {
      if (y > height * 0.95f) return;
      if (rtl)
        o.text(x + w - em, y, row, {1, 1, 1, 0.85f}, render::TextAlign::right, scale);
      else
        o.text(x + em, y, row, {1, 1, 1, 0.85f}, render::TextAlign::left, scale);
      y += line;
    }
}

}  // namespace

void print_text_costs(const std::string& device, int frames) {
  std::vector<std::string> problems;
  const Catalogue all = read_catalogue(data_dir() / "po" / "mallet.pot", problems);
  if (all.msgids.empty()) {
    std::printf("text: %s\n\n", problems.empty() ? "no texts" : problems.front().c_str());
    return;
  }
  const VkExtent2D size{1920, 1080};
  const Scene scene = config::load_scene(default_scene());
  render::HeadlessOptions o;
  o.size = size;
  o.device = device;
  o.validation = render::Validation::off;
  o.cache_dir = "";
  render::HeadlessRenderer r(scene, o);
  render::FrameState state;
  state.mallet_centre = {scene.targets.at(3).x_max + 0.004, 0.035};
  auto time_frame = [&](const render::FrameState& s) {
    std::vector<double> ms;
    for (int i = 0; i < frames; ++i) {
      const auto t0 = Clock::now();
      r.draw(s);
      ms.push_back(elapsed_ms(t0));
    }
    return median_ms(ms);
  };
  r.draw(state);
  const double bare = time_frame(state);
  double panel = 0;  // the page's panel without its text: what the text adds is the rest
  {
    const auto font = render::overlay_font(size);
    render::Overlay overlay(*font);
    draw_page(overlay, {}, 1920.0f, 1080.0f);
    render::FrameState with = state;
    with.overlay = &overlay;
    r.draw(with);
    panel = time_frame(with);
  }
  std::printf("text: a page of the catalogue's %zu texts at 1920x1080, the overlay built every frame (median of %d)\n",
              all.msgids.size(), frames);
  std::printf("| %-8s | %16s | %16s | %15s | %15s | %11s | %12s |\n", "language", "1st overlay ms", "later overlay ms",
              "frame ms", "text's share ms", "texts set", "glyphs drawn");
  std::printf("|----------|------------------|------------------|-----------------|-----------------|-------------|"
              "--------------|\n");
  for (const std::string language : {"en", "ar", "hi"}) {
    start_visitor_language(language, problems);
    const auto font = render::overlay_font(size);
    render::Overlay overlay(*font);
    auto build = [&] {
      overlay.clear();
      draw_page(overlay, all.msgids, 1920.0f, 1080.0f);
    };
    auto t0 = Clock::now();
    build();
    const double first = elapsed_ms(t0);
    const std::uint64_t set_first = font->shapings();
    std::vector<double> later;
    for (int i = 0; i < frames; ++i) {
      t0 = Clock::now();
      build();
      later.push_back(elapsed_ms(t0));
    }
    render::FrameState with = state;
    with.overlay = &overlay;
    r.draw(with);  // the atlas's first copy to the GPU
    const double frame = time_frame(with);
    std::printf("| %-8s | %16.2f | %16.3f | %15.2f | %15.2f | %5llu, %4llu | %12zu |\n", language.c_str(), first,
                median_ms(later), frame, frame - panel, static_cast<unsigned long long>(set_first),
                static_cast<unsigned long long>(font->shapings() - set_first), font->glyphs_drawn());
  }
  use_visitor_language("en");
  std::printf("(the frame without any overlay: %.2f ms; with the page's panel alone: %.2f ms. Texts set: on the first "
              "frame, then on all later frames together: 0 is nothing set twice)\n\n",
              bare, panel);
}

}  // namespace mallet::app
