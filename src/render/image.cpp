#include "render/image.hpp"
