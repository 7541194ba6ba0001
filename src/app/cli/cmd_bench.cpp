#include "app/cli/commands.hpp"
#include "app/bench/bench_commands.hpp"

namespace mallet::app {

void register_bench(CLI::App& app) {
  CLI::App* bench = app.add_subcommand("bench", "Benchmarks: programs that print tables (speed, measured here)");
  bench->require_subcommand(1);
  add_bench_audio(*bench);
  add_bench_input(*bench);
  add_bench_render(*bench);
  add_bench_report(*bench);
  add_bench_latency(*bench);
  add_bench_prediction(*bench);
  add_bench_soak(*bench);
}

}  // namespace mallet::app
