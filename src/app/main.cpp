// The `mallet` command line. Exit status: 0 success, 1 a failure of the machine
// (cannot write a file, a device), 2 bad input (a file, a flag) — with one line on
// stderr naming the file, the place and the problem.
#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>

#include "app/cli/commands.hpp"
#include "core/file_error.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "Mallet: a virtual xylophone (wood) and glockenspiel (metal) you can feel.\n"
      "At each strike the on-screen mallet bounces with the material's visual vibration,\n"
      "a voice coil in the stick plays Eq. 1 on one audio channel and the speaker plays\n"
      "the note on the other.\n",
      "mallet"};
  app.set_version_flag("--version", std::string(MALLET_VERSION));
  app.require_subcommand(1);
  app.footer(R"(Exit status: 0 ok, 1 failure (I/O, device), 2 bad input.
Run `mallet <command> --help` for each command's options and file formats.)");

  mallet::app::register_commands(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::RuntimeError& e) {  // a command's own status (finish_with): it said why
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  } catch (const mallet::FileError& e) {
    std::fprintf(stderr, "mallet: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mallet: %s\n", e.what());
    return 1;
  }
  for (const std::string& line : mallet::app::lines_when_done()) std::fprintf(stderr, "%s\n", line.c_str());
  return 0;
}
