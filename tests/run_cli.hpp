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

inline CliResult run_mallet(const std::string& args) {
  const std::string command = std::string(MALLET_TEST_BINARY) + " " + args + " 2>&1";
  CliResult r;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe)) r.output += buf.data();
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

}  // namespace mallet::test
