#include "render/font_atlas.hpp"
