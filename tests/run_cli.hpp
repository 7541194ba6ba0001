#pragma once
// Runs the real `mallet` binary the way a researcher's script does.
#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace mallet::test {

struct CliResult {
  int status = -1;
  std::string output;  //!< stdout and stderr together
};

//! Runs a shell command line with stderr joined to stdout.
inline CliResult run_command(const std::string& command_line) {
  const std::string command = command_line + " 2>&1";
  CliResult r;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe)) r.output += buf.data();
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

inline CliResult run_mallet(const std::string& args) {
  return run_command(std::string(MALLET_TEST_BINARY) + " " + args);
}

}  // namespace mallet::test
