// `mallet bench render`: ms per frame of the offscreen renderer (median of N frames, the
// GPU work and the read-back, waited for), for the floor (clear + read-back) and the
// percussion scene without and with the mallet's analytic shadow and with each
// antialiasing option, all over the renderer's cached background; the scene drawn whole
// every frame (no cache), for comparison; each option's image error against a 4×-supersampled reference
// of the same frame (rendered at twice the width and height, box-filtered down in
// linear light, as a multisample resolve into an sRGB image averages);
// start-up to first frame with a cold and a warm pipeline cache.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "render/detailed_model.hpp"
#include "app/bench/bench_kiosk_child.hpp"
#include "app/bench/bench_kiosk_cpu.hpp"
#include "app/bench/bench_render_text.hpp"
#include "app/bench/bench_report.hpp"
#include "app/bench/bench_commands.hpp"
#include "core/data_paths.hpp"
#include "render/render_setup.hpp"
#include "core/config/scene_config.hpp"
#include "render/image.hpp"
#include "render/scene_view.hpp"
#include "render/vk_error.hpp"

namespace mallet::app {

//! The reference's box filter averages light, not sRGB codes, as an MSAA resolve into an
//! sRGB image does: codes → linear, mean, → codes.
render::Image downsample_linear_light(const render::Image& image, int factor) {
  auto to_linear = [](std::uint8_t c) { return render::srgb_to_linear(c / 255.0); };
  auto to_code = [](double v) {
    const double s = v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
    return static_cast<std::uint8_t>(std::lround(std::clamp(s, 0.0, 1.0) * 255));
  };
  render::Image out(image.width / factor, image.height / factor);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 4; ++c) {
        double sum = 0;
        for (int dy = 0; dy < factor; ++dy)
          for (int dx = 0; dx < factor; ++dx) {
            const std::uint8_t v = image.at(x * factor + dx, y * factor + dy)[c];
            sum += c == 3 ? v / 255.0 : to_linear(v);
          }
        const double mean = sum / (factor * factor);
        out.at(x, y)[c] = c == 3 ? static_cast<std::uint8_t>(std::lround(mean * 255)) : to_code(mean);
      }
  return out;
}

VkSampleCountFlagBits samples_of(int n) {
  return n == 8 ? VK_SAMPLE_COUNT_8_BIT : n == 4 ? VK_SAMPLE_COUNT_4_BIT : n == 2 ? VK_SAMPLE_COUNT_2_BIT
                                                                                : VK_SAMPLE_COUNT_1_BIT;
}

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct TimingRow {
  std::string what;
  double median_ms = 0, p95_ms = 0;
  double rms = -1, differing = -1;  // against the reference; < 0: not measured
};

//! The shipped models with both bars replaced by detailed ones (bench_detailed_model.hpp).
struct DetailedModels {
  explicit DetailedModels(const std::filesystem::path& folder) : dir(folder) {
    std::filesystem::create_directories(dir);
    for (const auto& entry : std::filesystem::directory_iterator(render::models_dir()))
      if (entry.path().extension() == ".glb")
        std::filesystem::copy_file(entry.path(), dir / entry.path().filename(),
                                   std::filesystem::copy_options::overwrite_existing);
    // The shipped bars' material factors (tools/gen_models), without the wood's grain.
    triangles_per_bar = render::write_detailed_bar(dir / "wood_bar.glb", kCells, {0.30, 0.10, 0.045, 1.0}, 0.0, 0.55);
    render::write_detailed_bar(dir / "metal_bar.glb", kCells, {0.85, 0.85, 0.88, 1.0}, 1.0, 0.25);
  }
  static constexpr int kCells = 72;  // 12 · 72² = 62 208 triangles a bar
  std::filesystem::path dir;
  std::size_t triangles_per_bar = 0;
};

//! A frame the visitor sees: the mallet just above a bar, its shadow on two bars.
render::FrameState bench_state(const Scene& scene) {
  const Target& a = scene.targets.at(3);
  render::FrameState s;
  s.mallet_centre = {a.x_max + 0.004, 0.035};
  return s;
}

TimingRow time_frames(render::HeadlessRenderer& r, const render::FrameState& state, int frames, const std::string& what) {
  r.draw(state);  // warm-up: pipelines compiled, attachments made
  std::vector<double> ms;
  for (int i = 0; i < frames; ++i) {
    const auto t0 = Clock::now();
    r.draw(state);
    ms.push_back(ms_since(t0));
  }
  std::sort(ms.begin(), ms.end());
  return {what, ms[ms.size() / 2], ms[std::min(ms.size() - 1, ms.size() * 95 / 100)]};
}

void run(double kiosk_cpu_s, const std::filesystem::path& scene_file, int frames,
         const std::vector<std::string>& sizes,
         const std::string& device) {
  const Scene scene = config::load_scene(scene_file);
  const render::FrameState state = bench_state(scene);
  // A pipeline cache of this run's own (empty: the first start-up is cold), removed at the end.
  const latency::TempDir tmp("mallet-bench-render");
  const auto tmp_cache = tmp.path() / "pipeline-cache";

  // Start-up: context, pipelines (cold, then warm cache), first frame read back.
  double cold = 0, warm = 0;
  std::string device_name;
  for (int pass = 0; pass < 2; ++pass) {
    render::HeadlessOptions o;
    o.size = {1920, 1080};
    o.cache_dir = tmp_cache;
    o.device = device;
    o.validation = render::Validation::off;
    const auto t0 = Clock::now();
    render::HeadlessRenderer r(scene, o);
    r.render(state);
    (pass == 0 ? cold : warm) = ms_since(t0);
    device_name = r.context().device_name();
  }
  std::printf("device: %s; %d frames per row; ms per frame incl. read-back (median, p95)\n\n", device_name.c_str(),
              frames);
  std::printf("start-up to first 1920x1080 frame: %.0f ms with a cold pipeline cache, %.0f ms warm\n\n", cold, warm);

  const DetailedModels detailed(tmp_cache / "detailed-models");
  std::printf("detailed bars: %zu triangles each (the shipped bar: 12), %zu in the scene's bars\n\n",
              detailed.triangles_per_bar, detailed.triangles_per_bar * scene.targets.size());
  for (const std::string& size_text : sizes) {
    const VkExtent2D size = render::parse_size(size_text, "--sizes");
    auto make = [&](int msaa, bool shadow, VkExtent2D extent, bool background_cache = true, int background_msaa = 1,
                    const std::filesystem::path& models = {}) {
      render::HeadlessOptions o;
      o.models = models;
      o.size = extent;
      o.settings.samples = samples_of(msaa);
      o.settings.shadow = shadow;
      o.settings.background_cache = background_cache;
      o.settings.background_samples = samples_of(background_msaa);
      o.device = device;
      o.validation = render::Validation::off;
      o.cache_dir = tmp_cache;
      return std::make_unique<render::HeadlessRenderer>(scene, o);
    };
    // The reference: 4 samples per pixel on a regular grid, box-filtered.
    render::Image reference =
        downsample_linear_light(make(1, true, {size.width * 2, size.height * 2})->render(state), 2);

    std::vector<TimingRow> rows;
    {
      auto r = make(1, false, size);
      render::FrameState floor = state;
      floor.draw_instruments = false;
      floor.draw_mallet = false;
      rows.push_back(time_frames(*r, floor, frames, "floor: clear + read-back"));
      rows.push_back(time_frames(*r, state, frames, "scene, no shadow, no AA"));
    }
    {  // what the cached background saves: every frame draws every instrument
      auto r = make(1, true, size, false);
      TimingRow row = time_frames(*r, state, frames, "scene + shadow, whole, no AA");
      const render::ImageDiff d = render::compare_images(r->read_back(), reference, 3);
      row.rms = d.rms;
      row.differing = d.differing_fraction * 100;
      rows.push_back(row);
    }
    {  // a museum's detailed bars: the shadow is shaded on the screen, whatever the triangles;
       // a lit bar (the one under the mallet) is still redrawn with its triangles
      for (const bool cached : {true, false}) {
        auto r = make(1, true, size, cached, 1, detailed.dir);
        rows.push_back(time_frames(*r, state, frames,
                                   "detailed bars, " + std::string(cached ? "shadow" : "whole")));
      }
      render::FrameState lit = state;
      lit.bar_lights = {BarLight{scene.targets.at(2).id, 0.2f}, BarLight{}};
      auto shipped = make(1, true, size);
      rows.push_back(time_frames(*shipped, lit, frames, "scene + shadow + a lit bar, no AA"));
      auto r = make(1, true, size, true, 1, detailed.dir);
      rows.push_back(time_frames(*r, lit, frames, "detailed bars, shadow + a lit bar"));
    }
    for (int background_msaa : {2, 4, 8}) {  // antialiased once, per image size
      auto r = make(1, true, size, true, background_msaa);
      if (!render::supports_samples(r->context(), samples_of(background_msaa))) {
        rows.push_back({"bg MSAA " + std::to_string(background_msaa) + "x: not offered", 0, 0});
        continue;
      }
      TimingRow row = time_frames(*r, state, frames, "scene + shadow, bg MSAA " + std::to_string(background_msaa) + "x");
      const render::ImageDiff d = render::compare_images(r->read_back(), reference, 3);
      row.rms = d.rms;
      row.differing = d.differing_fraction * 100;
      rows.push_back(row);
    }
    for (int msaa : {1, 2, 4, 8}) {
      std::unique_ptr<render::HeadlessRenderer> r;
      try {
        r = make(msaa, true, size);
      } catch (const render::RenderError& e) {
        rows.push_back({"MSAA " + std::to_string(msaa) + "x: not offered", 0, 0});
        continue;
      }
      TimingRow row = time_frames(*r, state, frames,
                            msaa == 1 ? std::string("scene + shadow, no AA") : "scene + shadow, MSAA " +
                                                                                  std::to_string(msaa) + "x");
      const render::ImageDiff d = render::compare_images(r->read_back(), reference, 3);
      row.rms = d.rms;
      row.differing = d.differing_fraction * 100;
      rows.push_back(row);
    }
    std::printf("%s\n", size_text.c_str());
    std::printf("| %-28s | %9s | %8s | %8s | %13s | %12s |\n", "frame", "median ms", "p95 ms", "x floor",
                "RMS vs 4xSS", "px > 3/255 %");
    std::printf("|%s|%s|%s|%s|%s|%s|\n", std::string(30, '-').c_str(), std::string(11, '-').c_str(),
                std::string(10, '-').c_str(), std::string(10, '-').c_str(), std::string(15, '-').c_str(),
                std::string(14, '-').c_str());
    for (const TimingRow& row : rows) {
      const std::string rms = row.rms >= 0 ? fmt::format("{:.3f}", row.rms) : "";
      const std::string diff = row.rms >= 0 ? fmt::format("{:.3f}", row.differing) : "";
      if (row.median_ms == 0) {
        std::printf("| %-28s | %9s | %8s | %8s | %13s | %12s |\n", row.what.c_str(), "-", "-", "-", "-", "-");
        continue;
      }
      std::printf("| %-28s | %9.2f | %8.2f | %8.2f | %13s | %12s |\n", row.what.c_str(), row.median_ms, row.p95_ms,
                  row.median_ms / rows[0].median_ms, rms.c_str(), diff.c_str());
    }
    std::printf("\n");
  }
  print_text_costs(device, frames);
  if (kiosk_cpu_s > 0) {
    std::fflush(stdout);
    const std::vector<KioskCpuRow> cpu = measure_kiosk_cpu(1920, 1080, kiosk_cpu_s, device);
    std::printf("%s", markdown(kiosk_cpu_table(cpu, 1920, 1080)).c_str());
  }
}

}  // namespace

void add_bench_render(CLI::App& bench) {
  auto scene = std::make_shared<std::filesystem::path>(default_scene());
  auto frames = std::make_shared<int>(200);
  auto sizes = std::make_shared<std::vector<std::string>>(std::vector<std::string>{"1280x720", "1920x1080"});
  auto device = std::make_shared<std::string>();
  auto kiosk_cpu_s = std::make_shared<double>(10.0);
  CLI::App* cmd = bench.add_subcommand("render", "Offscreen renderer: ms per frame, shadow and antialiasing costs");
  cmd->footer(R"(Prints, per size: the floor (clear + read-back), the scene without and with the mallet's
analytic shadow, the scene drawn whole every frame (without the cached background of the
static instruments), and each antialiasing option (MSAA 1/2/4/8x) with its image error against
a 4x-supersampled reference of the same frame (RMS in 1/255 units; share of pixels off by
more than 3/255). Also start-up to the first frame with a cold and a warm pipeline cache, and
the text's cost: a page of every text of the catalogue in en, ar and hi over the scene at
1920x1080, the overlay built every frame (its first build, setting every text and drawing
every glyph, and a later one), the frame with and without it.
Then the real kiosk's CPU at 1920x1080, fullscreen on its own Xvfb with its sound on its own
JACK server: % of one core in the attract mode with nobody there, during play (an XTest
pointer sweeping over the bars) and still (the pointer at rest: no frame is drawn), with the
frame budget ([render] max_fps = the refresh) and without it (mallet run --no-frame-cap);
needs Xvfb and jackd (--kiosk-cpu-seconds 0: skip it).)");
  cmd->add_option("--scene", *scene, "Scene file")->capture_default_str()->check(CLI::ExistingFile);
  cmd->add_option("--frames", *frames, "Frames timed per row (median reported)")->capture_default_str()
      ->check(CLI::Range(10, 100000));
  cmd->add_option("--sizes", *sizes, "Image sizes")->capture_default_str();
  cmd->add_option("--device", *device, "Vulkan device (substring of its name)");
  cmd->add_option("--kiosk-cpu-seconds", *kiosk_cpu_s, "Seconds per phase of the kiosk's CPU (0: skip it)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 600.0));
  cmd->callback([=] { run(*kiosk_cpu_s, *scene, *frames, *sizes, *device); });
}

}  // namespace mallet::app
