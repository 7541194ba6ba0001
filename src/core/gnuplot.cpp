#include "core/gnuplot.hpp"

#include <cstdlib>

namespace mallet {

bool have_gnuplot() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

bool run_gnuplot(const std::filesystem::path& dir, const std::string& script) {
  const std::string cmd = "cd '" + dir.string() + "' && gnuplot '" + script + "' 2>&1";
  return std::system(cmd.c_str()) == 0;
}

}  // namespace mallet
