#include "app/commands.hpp"

namespace mallet::app {

namespace {
int g_exit_status = 0;
}

int exit_status() { return g_exit_status; }
void set_exit_status(int status) { g_exit_status = status; }

void register_commands(CLI::App& app) {
  register_simulate(app);
  register_scene(app);
  register_analyze(app);
  register_trajectory(app);
  register_audio(app);
  register_bench(app);
  register_wiimote(app);
  register_calibrate(app);
  register_render(app);
  register_run(app);
  register_study(app);
}

}  // namespace mallet::app
