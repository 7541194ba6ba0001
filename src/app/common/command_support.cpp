#include "app/common/command_support.hpp"

#include <cstdio>

#include <fmt/format.h>

#include "core/pixel_size.hpp"
#include "core/time.hpp"

namespace mallet::app {

namespace {
std::vector<std::string> g_when_done;
}  // namespace

void finish_with(int status) {
  if (status != 0) throw CLI::RuntimeError(status);
}

CLI::Validator positive_at_most(double most) {
  const std::string hi = most > 0 ? fmt::format("{:g}", most) : "";
  const std::string want = most > 0 ? std::string("must be > 0 and at most ") + hi : "must be > 0";
  return CLI::Validator(
      [most, want](std::string& value) {
        double v = 0;
        if (!CLI::detail::lexical_cast(value, v) || !(v > 0) || (most > 0 && v > most)) return want + ", got " + value;
        return std::string();
      },
      most > 0 ? std::string("in (0, ") + hi + "]" : "> 0");
}

CLI::Validator seconds() {
  return CLI::Validator(
      [](std::string& value) {
        double s = 0;
        if (CLI::detail::lexical_cast(value, s) && from_seconds(s)) return std::string();
        return "must be a finite number of seconds, got " + value;
      },
      "");
}

CLI::Validator pixel_size() {
  return CLI::Validator(
      [](std::string& value) {
        const Result<PixelSize, std::string> size = parse_pixel_size(value);
        return size ? std::string() : size.error();
      },
      "WIDTHxHEIGHT");
}

void say_when_done(std::string line) { g_when_done.push_back(std::move(line)); }
const std::vector<std::string>& lines_when_done() { return g_when_done; }

}  // namespace mallet::app
