#include "render/render_setup.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <thread>
#include <utility>

#include <fmt/format.h>

#include "core/data_paths.hpp"
#include "core/catalogue_file.hpp"
#include "core/journal.hpp"
#include "core/visitor_language.hpp"
#include "core/pixel_size.hpp"
#include "core/file_error.hpp"
#include "render/vk_error.hpp"

namespace mallet::render {

render::Validation validation_from_env() {
  const char* v = std::getenv("MALLET_VK_VALIDATION");
  if (v && std::string(v) == "required") return render::Validation::required;
  if (v && *v) return std::string(v) == "0" ? render::Validation::off : render::Validation::if_available;
#ifdef NDEBUG
  return render::Validation::off;
#else
  return render::Validation::if_available;
#endif
}

VkExtent2D parse_size(const std::string& text, const std::string& option) {
  const Result<PixelSize, std::string> size = parse_pixel_size(text);
  if (!size) throw FileError(option, 0, 0, size.error());
  return {size->width, size->height};
}

std::filesystem::path models_dir() { return data_dir() / "models"; }

std::unique_ptr<render::Context> make_window_context(const std::string& device) {
  render::ContextOptions co;
  co.validation = validation_from_env();
  co.device_name = device;
  co.instance_extensions = render::WindowSystem::instance_extensions();
  co.swapchain = true;
  return std::make_unique<render::Context>(co);
}

render::WindowOptions window_options(const RenderConfig& r, const std::string& size, bool windowed) {
  render::WindowOptions wo;
  const VkExtent2D extent = parse_size(size, "--size");
  wo.width = static_cast<int>(extent.width);
  wo.height = static_cast<int>(extent.height);
  wo.fullscreen = !windowed;
  wo.hide_cursor = !windowed;
  wo.monitor = r.monitor;
  wo.present_mode = r.present_mode;
  wo.put_changes = r.software_present == SoftwarePresent::changes;
  return wo;
}

render::RenderSettings render_settings(const render::Context& ctx, const RenderConfig& r) {
  render::RenderSettings rs;
  // An explicit count is everything's: the background's own samples stay 1, the default.
  if (r.msaa == "auto")
    render::use_recommended_antialiasing(ctx, rs);
  else
    rs.samples = static_cast<VkSampleCountFlagBits>(std::stoi(r.msaa));
  rs.shadow = r.shadow;
  return rs;
}

std::vector<std::string> screen_texts() {
  static const std::vector<std::string> msgids = [] {
    std::vector<std::string> problems;
    return read_catalogue(data_dir() / "po" / "mallet.pot", problems).msgids;
  }();
  std::vector<std::string> texts{"0123456789 %.,:;()/-"};
  for (const std::string& id : msgids) texts.emplace_back(tr(id.c_str()));
  return texts;
}

std::unique_ptr<render::FontAtlas> overlay_font(VkExtent2D extent, const std::map<std::string, std::string>& fonts) {
  const float shorter = static_cast<float>(std::min(extent.width, extent.height));
  const float px = std::max(14.0f, shorter / 24.0f);
  render::FontChoice choice;
  for (const auto& [language, family] : fonts) choice.families.emplace(language, family);
  return std::make_unique<render::FontAtlas>(px, std::move(choice));
}

ProductWindow::ProductWindow(const RenderConfig& r, const std::string& device, const std::string& size, bool windowed,
                             const std::string& title)
    : device_name(device.empty() ? r.device : device),
      options(window_options(r, size, windowed)),
      ctx(make_window_context(device_name)),
      cache(std::make_unique<render::PipelineCache>(*ctx, render::PipelineCache::default_dir())) {
  options.title = title;
  max_fps_ = r.max_fps;
  window = std::make_unique<render::WindowTarget>(*ctx, options, &clock);
  aspect.set(static_cast<int>(window->extent().width), static_cast<int>(window->extent().height));
  font = overlay_font(window->extent(), r.fonts);
  font->warm(visitor_language(), screen_texts());
  overlay = std::make_unique<render::Overlay>(*font);
  if (const char* lose = std::getenv("MALLET_INJECT_DEVICE_LOST")) {
    std::stringstream in(lose);
    for (std::string n; std::getline(in, n, ',');)
      if (!n.empty()) inject_lost_at_.push_back(std::strtoull(n.c_str(), nullptr, 10));
    std::sort(inject_lost_at_.begin(), inject_lost_at_.end());
  }
}

void ProductWindow::set_max_fps(double max_fps) {
  if (max_fps == max_fps_) return;
  max_fps_ = max_fps;
  pacer_.set_max_fps(0);
}

void ProductWindow::say_pace(std::string line) {
  if (line == pace_said_) return;
  journal::info("{}", line);
  pace_said_ = std::move(line);
}

void ProductWindow::pace() {
  held_ns_ = 0;
  // A still scene: the last frame was not drawn, so no acquire held this loop back. It waits
  // for the grid's next frame start instead, in step with the display (or the budget's own
  // grid, below), so that nothing moving costs nothing but the wake-ups.
  auto wait_for_next_start = [this] {
    const Nanos now = monotonic_now();
    sleep_until_monotonic(clock.next_start(now + 1));
    held_ns_ = monotonic_now() - now;
  };
  if (max_fps_ < 0) {  // mallet run --no-frame-cap
    say_pace("render: frames not capped (--no-frame-cap)");
    if (window->still()) wait_for_next_start();
    return;
  }
  // A FIFO display is judged once from its first frames drawn back to back (the present
  // model's verdict, PresentClock::judged): none is held back until then.
  if (!clock.judged()) {
    if (pacer_.max_fps() > 0) pacer_.set_max_fps(0);
    if (window->still()) wait_for_next_start();
    return;
  }
  const double refresh = window->refresh_hz();
  const double cap = max_fps_ > 0 ? std::min(max_fps_, refresh) : refresh;
  const bool fifo = clock.pacing() == PresentPacing::fifo;
  const bool display_paces = fifo && !clock.unpaced();
  const bool pace = !display_paces || cap < refresh * 0.98;
  if (pace != (pacer_.max_fps() > 0)) pacer_.set_max_fps(pace ? cap : 0);
  // The line is made only when the choice changes, not on every frame.
  const PaceChoice choice{pace, display_paces, cap, refresh, clock.fast_frames(), window.get()};
  if (choice != pace_chosen_) {
    pace_chosen_ = choice;
    say_pace_choice(choice);
  }
  if (!pace) {
    if (window->still()) wait_for_next_start();
    return;
  }
  const Nanos now = monotonic_now();
  const Nanos wake = pacer_.begin(now);
  if (wake <= now) return;
  sleep_until_monotonic(wake);
  held_ns_ = monotonic_now() - now;
}

void ProductWindow::say_pace_choice(const PaceChoice& c) {
  const bool fifo = clock.pacing() == PresentPacing::fifo;
  const int unvoted = clock.unvoted_frames();
  const std::string judged =
      fmt::format("{} of its first {} frames came sooner than its {:.0f} Hz refresh{}", c.fast_frames,
                  PresentClock::kJudgedFrames, c.refresh,
                  unvoted > 0 ? fmt::format("; {} slower by their own work left out", unvoted) : std::string());
  if (!c.pace)
    say_pace(fmt::format("render: frames paced by the display ({}: {})", window->presentation(), judged));
  else if (c.display_paces)
    say_pace(fmt::format("render: frames paced at {:.0f} a second ([render] max_fps, below the display's {:.0f} Hz "
                         "refresh)",
                         c.cap, c.refresh));
  else
    say_pace(fmt::format("render: frames paced at {:.0f} a second, the display's refresh ({}: {})", c.cap,
                         window->presentation(), fifo ? "the display does not hold them back, " + judged
                                                      : std::string("nothing holds them back")));
}

bool ProductWindow::draw_or_recover(render::SceneRenderer& renderer, const render::FrameState& state,
                                    const std::function<void()>& drop, const std::function<void()>& make) {
  if (!inject_lost_at_.empty() && frames_ == inject_lost_at_.front()) {
    inject_lost_at_.erase(inject_lost_at_.begin());
    window->fail_next_draw(VK_ERROR_DEVICE_LOST);
  }
  try {
    const bool drawn = window->draw(renderer, state);
    frames_ += drawn;
    aspect.set(static_cast<int>(window->extent().width), static_cast<int>(window->extent().height));
    return drawn;
  } catch (const render::RenderError& lost) {
    if (lost.result() != VK_ERROR_DEVICE_LOST) throw;
    const Nanos at = monotonic_now();
    ++devices_lost_;
    journal::error("render: the Vulkan device was lost ({}); rebuilding the device, the pipelines and the "
                   "background (the sound and the remote's strikes go on)", lost.what());
    constexpr int kTries = 5;
    for (int attempt = 1;; ++attempt) {
      try {
        drop();  // before the device it was made on
        rebuild();
        make();
        break;
      } catch (const render::RenderError& e) {
        if (attempt == kTries) throw;
        journal::error("render: rebuilding failed ({}); trying again in 1 s ({} of {})", e.what(), attempt, kTries);
        std::this_thread::sleep_for(std::chrono::seconds(1));
      }
    }
    journal::notice("render: rebuilt on {} in {:.0f} ms; drawing again (device lost {} time(s))",
                    ctx->device_name().c_str(), to_seconds(monotonic_now() - at) * 1e3, devices_lost_);
    return false;
  }
}

void ProductWindow::rebuild() {
  if (window) kept_window = window->release_window();
  window.reset();  // its surface and swapchain, on the old instance and device
  cache.reset();
  ctx.reset();
  ctx = make_window_context(device_name);
  cache = std::make_unique<render::PipelineCache>(*ctx, render::PipelineCache::default_dir());
  window = std::make_unique<render::WindowTarget>(*ctx, options, &clock, kept_window);
  kept_window = nullptr;
}

HeadlessOptions kiosk_headless_options(const RenderConfig& r, VkExtent2D size, const std::string& device) {
  HeadlessOptions ho;
  ho.size = size;
  ho.auto_samples = r.msaa == "auto";
  if (!ho.auto_samples) ho.settings.samples = static_cast<VkSampleCountFlagBits>(std::stoi(r.msaa));
  ho.settings.shadow = r.shadow;
  ho.device = device.empty() ? r.device : device;
  return ho;
}

HeadlessRenderer::HeadlessRenderer(const Scene& scene, const HeadlessOptions& options) {
  render::ContextOptions co;
  co.validation = options.validation;
  co.device_name = options.device;
  ctx_ = std::make_unique<render::Context>(co);
  cache_ = std::make_unique<render::PipelineCache>(*ctx_, options.cache_dir);
  render::RenderSettings settings = options.settings;
  if (options.auto_samples) render::use_recommended_antialiasing(*ctx_, settings);
  const std::filesystem::path models = options.models.empty() ? models_dir() : options.models;
  renderer_ = std::make_unique<render::SceneRenderer>(*ctx_, scene, models, render::OffscreenTarget::kFormat, settings,
                                                      cache_->get());
  target_ = std::make_unique<render::OffscreenTarget>(*ctx_, options.size);
}

HeadlessRenderer::~HeadlessRenderer() {
  target_.reset();
  renderer_.reset();
  cache_.reset();  // saves the cache
  ctx_.reset();
}

}  // namespace mallet::render
