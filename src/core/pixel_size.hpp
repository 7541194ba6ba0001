#pragma once
// A size in pixels as the command line and the settings write it: "1280x720".
#include <string>
#include <string_view>

#include "core/result.hpp"

namespace mallet {

struct PixelSize {
  unsigned width = 0, height = 0;
};

//! WIDTHxHEIGHT, digits only, each side in [lo, hi]; else why not ("expected WIDTHxHEIGHT
//! such as 1280x720, got ...", "width and height must be 16..8192, got ...").
Result<PixelSize, std::string> parse_pixel_size(std::string_view text, unsigned lo = 16, unsigned hi = 8192);

}  // namespace mallet
