#include "core/pixel_size.hpp"

#include <charconv>

#include <fmt/format.h>

namespace mallet {

Result<PixelSize, std::string> parse_pixel_size(std::string_view text, unsigned lo, unsigned hi) {
  const auto side = [](std::string_view d, unsigned& out) {
    if (d.empty() || d.size() > 5 || d.find_first_not_of("0123456789") != std::string_view::npos) return false;
    std::from_chars(d.data(), d.data() + d.size(), out);
    return true;
  };
  PixelSize s;
  const std::size_t x = text.find('x');
  if (x == std::string_view::npos || !side(text.substr(0, x), s.width) || !side(text.substr(x + 1), s.height))
    return refused(fmt::format("expected WIDTHxHEIGHT such as 1280x720, got \"{}\"", text));
  if (s.width < lo || s.height < lo || s.width > hi || s.height > hi)
    return refused(fmt::format("width and height must be {}..{}, got {}", lo, hi, text));
  return s;
}

}  // namespace mallet
