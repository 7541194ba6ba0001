#include "input/camera/frame_stream.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "core/file_error.hpp"

namespace mallet::input::camera::test {

namespace {

constexpr std::string_view kMagic = "mallet-camera-stream 1";
constexpr std::string_view kKeys[] = {"t_ns", "sequence", "width", "height", "format", "bytes_per_line", "size", "led"};

template <typename T>
bool number(std::string_view s, T& out) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && end == s.data() + s.size();
}

}  // namespace

std::string format_frame_stream(const std::vector<StreamFrame>& frames) {
  std::string out(kMagic);
  out += '\n';
  for (const StreamFrame& f : frames) {
    const std::string led = f.led ? fmt::format("{:.3f},{:.3f}", f.led->x, f.led->y) : std::string("none");
    out += fmt::format("frame t_ns={} sequence={} width={} height={} format={} bytes_per_line={} size={} led={}\n",
                       f.t_ns, f.sequence, f.width, f.height, name_in(kPixelFormatNames, f.format), f.bytes_per_line,
                       f.bytes.size(), led);
    out.append(f.bytes.begin(), f.bytes.end());
    out += '\n';
  }
  return out;
}

std::vector<StreamFrame> parse_frame_stream(std::string_view data, const std::string& name) {
  std::size_t pos = 0;
  int index = 0;
  auto fail = [&](const std::string& why) -> FileError {
    return FileError(name, 0, 0, fmt::format("frame {} at byte {}: {}", index, pos, why));
  };
  auto line = [&](std::size_t max_len) {
    const std::size_t nl = data.find('\n', pos);
    if (nl == std::string_view::npos || nl - pos > max_len) throw fail("a header line without its newline");
    const std::string_view l = data.substr(pos, nl - pos);
    pos = nl + 1;
    return l;
  };
  if (line(64) != kMagic) {
    pos = 0;
    throw fail(fmt::format("not a camera stream (the first line must be \"{}\")", kMagic));
  }
  std::vector<StreamFrame> frames;
  while (pos < data.size()) {
    ++index;
    const std::size_t at = pos;
    std::string_view l = line(512);
    pos = at;  // errors name where the frame's line starts
    if (!l.starts_with("frame ")) throw fail("expected a line starting \"frame \"");
    l.remove_prefix(6);
    StreamFrame f;
    std::size_t size = 0;
    for (const std::string_view key : kKeys) {
      const std::size_t space = std::min(l.find(' '), l.size());
      const std::string_view field = l.substr(0, space);
      l.remove_prefix(std::min(space + 1, l.size()));
      if (!field.starts_with(key) || field.size() <= key.size() || field[key.size()] != '=')
        throw fail(fmt::format("expected {}=… where \"{}\" is", key, field));
      const std::string_view value = field.substr(key.size() + 1);
      bool ok = true;
      if (key == "t_ns") ok = number(value, f.t_ns);
      else if (key == "sequence") ok = number(value, f.sequence);
      else if (key == "width") ok = number(value, f.width) && f.width >= 1 && f.width <= 16384;
      else if (key == "height") ok = number(value, f.height) && f.height >= 1 && f.height <= 16384;
      else if (key == "bytes_per_line") ok = number(value, f.bytes_per_line);
      else if (key == "size") ok = number(value, size);
      else if (key == "format") {
        const std::optional<PixelFormat> fmt_value = value_named(kPixelFormatNames, value);
        if (!fmt_value) throw fail(fmt::format("format \"{}\": expected {}", value, quoted_names(kPixelFormatNames)));
        f.format = *fmt_value;
      } else if (value != "none") {
        const std::size_t comma = value.find(',');
        TruthPoint p;
        ok = comma != std::string_view::npos && number(value.substr(0, comma), p.x) &&
             number(value.substr(comma + 1), p.y) && std::isfinite(p.x) && std::isfinite(p.y);
        f.led = p;
      }
      if (!ok) throw fail(fmt::format("{} \"{}\" is not a valid value", key, value));
    }
    if (!l.empty()) throw fail(fmt::format("unexpected \"{}\" after led=", l));
    pos = data.find('\n', pos) + 1;
    if (size > data.size() - pos)
      throw fail(fmt::format("size {} runs past the end of the file ({} bytes left)", size, data.size() - pos));
    f.bytes.assign(data.begin() + static_cast<std::ptrdiff_t>(pos), data.begin() + static_cast<std::ptrdiff_t>(pos + size));
    pos += size;
    if (pos >= data.size() || data[pos] != '\n') throw fail("the frame's bytes are not followed by a newline");
    ++pos;
    frames.push_back(std::move(f));
  }
  return frames;
}

void write_frame_stream(const std::filesystem::path& path, const std::vector<StreamFrame>& frames) {
  const std::string text = format_frame_stream(frames);
  std::ofstream out(path, std::ios::binary);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out.flush()) throw FileError(path.string(), 0, 0, "cannot write");
}

std::vector<StreamFrame> read_frame_stream(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path.string(), 0, 0, "cannot open (does it exist?)");
  std::ostringstream buf;
  buf << in.rdbuf();
  return parse_frame_stream(buf.str(), path.string());
}

std::vector<StreamFrame> make_frame_stream(const StreamSpec& spec) {
  LedFrameSynth synth(spec.seed);
  std::vector<StreamFrame> out;
  std::vector<std::uint8_t> luma;
  const Nanos period = static_cast<Nanos>(std::llround(1e9 / spec.rate_hz));
  for (std::uint32_t seq = 0; out.size() < static_cast<std::size_t>(spec.frames); ++seq) {
    if (std::find(spec.dropped.begin(), spec.dropped.end(), seq) != spec.dropped.end()) continue;
    const double t = seq / spec.rate_hz;
    SynthScene scene = spec.scene;
    scene.spots.clear();
    SynthSpot led = spec.led;
    led.x += led.vx_px_per_s * t;
    led.y += led.vy_px_per_s * t;
    const bool hidden = std::find(spec.hidden.begin(), spec.hidden.end(), seq) != spec.hidden.end();
    if (!hidden) scene.spots.push_back(led);
    if (spec.reflection) scene.spots.push_back(*spec.reflection);
    synth.render(scene, luma);
    auto bytes = encode_frame(luma, scene.width, scene.height, spec.format, spec.bytes_per_line);
    if (!bytes) throw std::runtime_error(bytes.error());
    StreamFrame f{period * seq, seq, scene.width, scene.height, spec.format,
                  spec.format == PixelFormat::mjpeg ? 0 : spec.bytes_per_line, std::move(*bytes), std::nullopt};
    if (!hidden) f.led = TruthPoint{led.x, led.y};
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace mallet::input::camera::test
