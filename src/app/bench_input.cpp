// Placeholder so the tree links while this file is being written (replaced in this session).
#include "app/commands.hpp"

namespace mallet::app {
void add_bench_input(CLI::App&) {}
}  // namespace mallet::app
