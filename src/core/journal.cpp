#include "core/journal.hpp"

#include <cstdio>

namespace mallet::journal {

void write(int priority, std::string_view text) {
  fmt::memory_buffer line;
  fmt::format_to(std::back_inserter(line), "<{}>{}\n", priority, text);
  std::fwrite(line.data(), 1, line.size(), stderr);
}

}  // namespace mallet::journal
