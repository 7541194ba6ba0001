#include <cstdio>
#include <fstream>

#include <fmt/format.h>

#include "app/cli/commands.hpp"
#include "core/data_paths.hpp"
#include "app/offline/simulate.hpp"
#include "core/config/scene_config.hpp"
#include "core/file_error.hpp"
#include "core/ghost_player.hpp"
#include "core/scene_layout.hpp"
#include "app/common/command_support.hpp"

namespace mallet::app {

void register_trajectory(CLI::App& app) {
  struct Options {
    std::filesystem::path scene = default_scene();
    std::vector<int> targets;
    double start_s = 0.5;
    double interval_s = 0.5;
    double speed = 1.5;
    double rate_hz = 100;
    std::string space = "screen";
    std::filesystem::path out;
    SceneLayout layout = SceneLayout::landscape;
  };
  auto o = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("trajectory", "Script a trajectory that strikes bars at exact times and speeds");
  cmd->footer(R"(Writes a TRAJ.csv (t,x,y) for `mallet simulate`: the ghost player of the attract mode
strikes each target (ids from `mallet scene describe`) in turn, the k-th at
start + k·interval seconds, crossing the bar's surface at exactly that time with exactly
--speed m/s downwards, sampled at --rate Hz.)");
  cmd->add_option("--scene", o->scene, "Scene file")->capture_default_str();
  cmd->add_option("--targets", o->targets, "Target ids to strike, in order (e.g. 0,2,4,7)")->required()->delimiter(',');
  cmd->add_option("--start", o->start_s, "Time of the first strike (s)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--interval", o->interval_s, "Time between strikes (s)")
      ->capture_default_str()
      ->check(positive_at_most());
  cmd->add_option("--speed", o->speed, "Downward speed at contact (m/s)")
      ->capture_default_str()
      ->check(positive_at_most(100.0));
  cmd->add_option("--rate", o->rate_hz, "Samples per second")->capture_default_str()->check(CLI::Range(1.0, 100000.0));
  cmd->add_option("--space", o->space, "screen: normalised 0..1; world: sphere centre in metres")
      ->check(CLI::IsMember({"screen", "world"}))
      ->capture_default_str();
  cmd->add_option("--out", o->out, "Output CSV")->required();
  add_choice(*cmd, "--layout", o->layout, kSceneLayoutNames,
             "The scene as a landscape or a portrait screen lays it out (portrait: instruments stacked)");
  cmd->callback([o] {
    const Scene scene = laid_out(config::load_scene(o->scene), o->layout);
    std::vector<ScriptedStrike> strikes;
    for (std::size_t k = 0; k < o->targets.size(); ++k) {
      const int id = o->targets[k];
      if (id < 0 || id >= static_cast<int>(scene.targets.size()))
        throw FileError("--targets", 0, 0, "no target " + std::to_string(id) + " in " + scene.file + " (0.." +
                                               std::to_string(scene.targets.size() - 1) + ")");
      strikes.push_back({id, static_cast<Nanos>(std::llround((o->start_s + static_cast<double>(k) * o->interval_s) * 1e9)),
                         o->speed});
    }
    const GhostPath path = ghost_player(scene, strikes, o->rate_hz);
    for (std::size_t k = 0; k < strikes.size(); ++k) {
      if (path.contacts[k] != strikes[k].t_ns)
        std::fprintf(stderr, "mallet: warning: strike %zu (target %d) lands %.1f ms late: the mallet needs more time "
                             "to lift and travel (raise --interval)\n",
                     k, strikes[k].target, to_seconds(path.contacts[k] - strikes[k].t_ns) * 1e3);
    }
    std::ofstream f(o->out);
    if (!f) throw std::runtime_error(o->out.string() + ": cannot create");
    f << "t,x,y\n";
    for (const PointerSample& s : path.samples) {
      const Vec2 p = o->space == "screen" ? scene.screen_to_world.unmap({s.x, s.y}) : Vec2{s.x, s.y};
      if (s.t_ns < 0) continue;  // an approach before t = 0 is cut: TRAJ.csv starts at 0
      f << format_seconds(s.t_ns) << fmt::format(",{:.12g},{:.12g}\n", p.x, p.y);
    }
    f.flush();
    if (!f) throw std::runtime_error(o->out.string() + ": write failed");
    std::printf("wrote %s (%zu strikes, %zu samples)\n", o->out.string().c_str(), strikes.size(), path.samples.size());
  });
}

}  // namespace mallet::app
