// `mallet-bench`, the benchmarks' own program: the only one that links STK, XTest and JACK's
// client library, in its own package (mallet-bench), so that a kiosk carries none of them.
// `mallet bench …` runs it (cli/cmd_bench.cpp) with argv[0] "mallet" and argv[1] "bench";
// it then speaks as that command always has: `mallet bench report --help` says
// "Usage: mallet bench report", a failure "mallet: …". Run directly, it is `mallet-bench
// report …`. Exit status: 0 ok, 1 failure (I/O, device, a server missing), 2 bad input.
#include <filesystem>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

#include "app/bench/bench_commands.hpp"

namespace {

constexpr const char* kAbout =
    "Mallet's benchmarks: programs that print tables (speed, measured here), and the report\n"
    "that gathers them. The latency and soak benchmarks run the kiosk, mallet, beside this\n"
    "program.\n";
constexpr const char* kBenchAbout = "Benchmarks: programs that print tables (speed, measured here)";

void add_benchmarks(CLI::App& bench) {
  bench.require_subcommand(1);
  mallet::app::add_bench_audio(bench);
  mallet::app::add_bench_input(bench);
  mallet::app::add_bench_render(bench);
  mallet::app::add_bench_report(bench);
  mallet::app::add_bench_latency(bench);
  mallet::app::add_bench_prediction(bench);
  mallet::app::add_bench_soak(bench);
  mallet::app::add_bench_actuator(bench);
}

}  // namespace

int main(int argc, char** argv) {
  const bool forwarded_by_mallet = argc >= 2 && std::filesystem::path(argv[0]).filename() == "mallet" &&
                               std::string_view(argv[1]) == "bench";
  if (forwarded_by_mallet) {
    CLI::App forwarded{kAbout, "mallet"};
    forwarded.footer(mallet::app::exit_status_footer("mallet"));
    add_benchmarks(*forwarded.add_subcommand("bench", kBenchAbout));
    forwarded.require_subcommand(1);
    return mallet::app::run_command_line(forwarded, argc, argv);
  }
  CLI::App app{kAbout, "mallet-bench"};
  app.set_version_flag("--version", std::string(MALLET_VERSION));
  app.footer(mallet::app::exit_status_footer("mallet-bench") +
             "\n`mallet bench <command>` runs the same commands with the same options.");
  add_benchmarks(app);
  return mallet::app::run_command_line(app, argc, argv);
}
