// Placeholder so the tree links while this file is being written (replaced in this session).
#include "app/commands.hpp"

namespace mallet::app {
void register_calibrate(CLI::App&) {}
}  // namespace mallet::app
