// `mallet bench …`: the benchmarks are a program of their own, mallet-bench (the package
// mallet-bench), so that the kiosk links and ships nothing only a benchmark uses (STK, XTest,
// JACK's client). `mallet bench ARGS…` execs it with the same arguments: its output and its
// exit status are the benchmark's own, as they were when it lived in this program.
#include <errno.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "app/cli/commands.hpp"
#include "app/common/programs.hpp"

namespace mallet::app {

int run_bench_program(const std::vector<std::string>& args) {
  const std::filesystem::path program = sibling_program("mallet-bench");
  if (program.empty()) {
    std::fprintf(stderr,
                 "mallet bench: the benchmarks are a program of their own, mallet-bench, which is not installed: "
                 "install the Debian package mallet-bench (apt install mallet-bench)\n");
    return 1;
  }
  // argv[0] "mallet" and then "bench": mallet-bench then speaks as `mallet bench` (its usage
  // lines and its errors), bench_main.cpp.
  std::vector<std::string> words = {"mallet", "bench"};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  std::fflush(nullptr);
  execv(program.c_str(), argv.data());
  std::fprintf(stderr, "mallet bench: cannot run %s: %s\n", program.c_str(), std::strerror(errno));
  return 1;
}

void register_bench(CLI::App& app) {
  CLI::App* bench = app.add_subcommand(
      "bench", "Benchmarks: programs that print tables (speed, measured here); runs mallet-bench");
  // Everything after `bench` is mallet-bench's (main.cpp hands it over before parsing; this is
  // the same for a command line that reaches the parser).
  bench->prefix_command();
  bench->allow_extras();
  bench->set_help_flag();
  bench->callback([bench] { finish_with(run_bench_program(bench->remaining())); });
}

}  // namespace mallet::app
