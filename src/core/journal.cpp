#include "core/journal.hpp"

#include <cstdio>

namespace mallet::journal {

void write(int priority, fmt::string_view format, fmt::format_args args) {
  fmt::memory_buffer line;
  fmt::format_to(std::back_inserter(line), "<{}>", priority);
  fmt::vformat_to(std::back_inserter(line), format, args);
  line.push_back('\n');
  std::fwrite(line.data(), 1, line.size(), stderr);
}

}  // namespace mallet::journal
