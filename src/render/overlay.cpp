#include "render/overlay.hpp"
