#include "app/cli/commands.hpp"

namespace mallet::app {

void register_commands(CLI::App& app) {
  register_simulate(app);
  register_scene(app);
  register_analyze(app);
  register_trajectory(app);
  register_audio(app);
  register_bench(app);
  register_wiimote(app);
  register_camera(app);
  register_calibrate(app);
  register_render(app);
  register_run(app);
  register_study(app);
  register_config(app);
  register_doctor(app);
}

}  // namespace mallet::app
