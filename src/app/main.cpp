// The `mallet` command line. Exit status: 0 success, 1 a failure of the machine
// (cannot write a file, a device), 2 bad input (a file, a flag) — with one line on
// stderr naming the file, the place and the problem.
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/cli/commands.hpp"

int main(int argc, char** argv) {
  // `mallet bench …` is the program mallet-bench's (cli/cmd_bench.cpp): handed over whole.
  if (argc >= 2 && std::string_view(argv[1]) == "bench")
    return mallet::app::run_bench_program(std::vector<std::string>(argv + 2, argv + argc));

  CLI::App app{
      "Mallet: a virtual xylophone (wood) and glockenspiel (metal) you can feel.\n"
      "At each strike the on-screen mallet bounces with the material's visual vibration,\n"
      "a voice coil in the stick plays Eq. 1 on one audio channel and the speaker plays\n"
      "the note on the other.\n",
      "mallet"};
  app.set_version_flag("--version", std::string(MALLET_VERSION));
  app.require_subcommand(1);
  app.footer(mallet::app::exit_status_footer("mallet"));

  mallet::app::register_commands(app);
  return mallet::app::run_command_line(app, argc, argv);
}
