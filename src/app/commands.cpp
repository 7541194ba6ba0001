#include "app/commands.hpp"

namespace mallet::app {

namespace {
int g_exit_status = 0;
std::vector<std::string> g_when_done;
}  // namespace

int exit_status() { return g_exit_status; }
void set_exit_status(int status) { g_exit_status = status; }
void say_when_done(std::string line) { g_when_done.push_back(std::move(line)); }
const std::vector<std::string>& lines_when_done() { return g_when_done; }

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
  register_config(app);
  register_doctor(app);
}

}  // namespace mallet::app
