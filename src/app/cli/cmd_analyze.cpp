#include <cstdio>

#include <fmt/format.h>

#include "app/offline/analyze.hpp"
#include "app/cli/commands.hpp"
#include "core/data_paths.hpp"
#include "app/common/settings_source.hpp"
#include "app/offline/simulate.hpp"
#include "core/config/app_config_loader.hpp"
#include "core/config/scene_config.hpp"
#include "core/named.hpp"

namespace mallet::app {

void register_analyze(CLI::App& app) {
  struct Options {
    std::filesystem::path dir;
    std::filesystem::path scene = default_scene();
    std::optional<std::filesystem::path> config = default_settings();
    std::optional<std::filesystem::path> config_dir;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "analyze", "Fit Eq. 1 to what `mallet simulate` wrote and compare with the material table");
  cmd->footer(R"(Fit Eq. 1, Q(t) = a·e^(−B·t)·sin(2π·f·t + φ), to each impact that `mallet simulate`
wrote into DIR (cursor.csv's offset column for the visual vibration, the actuator
channel of audio.wav for the actuator) and print the fitted A, B, f next to the
scene's material table. A_fit = a / v (visual, seconds) or a / (gain·v) (actuator).)");
  cmd->add_option("--dir", o->dir, "Directory written by mallet simulate")->required()->check(CLI::ExistingDirectory);
  cmd->add_option("--scene", o->scene, "Scene the simulation used (for its material table)")->capture_default_str();
  add_settings_options(*cmd, o->config, o->config_dir);  // those the simulation used (gain, routing)
  cmd->callback([o] {
    const AppConfig config = command_settings(o->config, o->config_dir, "analyze");
    const Scene scene = config::load_scene(o->scene);
    const auto results = analyze_simulation(o->dir, config.audio.routing.actuator);
    std::printf("%-14s %-9s %7s | %-39s | %-39s\n", "impact t (s)", "material", "v (m/s)",
                "visual:   A (s)      B (1/s)     f (Hz)", "actuator: A         B (1/s)     f (Hz)");
    for (const ImpactAnalysis& a : results) {
      const Material* m = find_named(scene.materials, a.material);
      auto row = [](const DampedSineFit& fit, double scale) {
        if (!fit.ok) return fmt::format("{:<33}", "(too short to fit)");
        return fmt::format("{:<11.7g} {:10.6f} {:10.6f}", fit.amplitude / scale, fit.decay_per_s, fit.freq_hz);
      };
      std::printf("%-14s %-9s %7.4f | fit   %s | fit   %s\n", format_seconds(a.t_ns).c_str(), a.material.c_str(),
                  a.velocity, row(a.visual, a.velocity).c_str(),
                  row(a.actuator, config.actuator.gain * a.velocity).c_str());
      if (m)
        std::printf("%-14s %-9s %7s | table %-11.7g %10.6f %10.6f | table %-11.7g %10.6f %10.6f\n", "", "", "",
                    m->visual.amplitude, m->visual.decay_per_s, m->visual.freq_hz, m->actuator.amplitude,
                    m->actuator.decay_per_s, m->actuator.freq_hz);
    }
  });
}

}  // namespace mallet::app
