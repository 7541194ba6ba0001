#include "input/camera/v4l2_node.hpp"

#include <fcntl.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <linux/videodev2.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include <fmt/format.h>

namespace mallet::input::camera {

int xioctl(int fd, unsigned long request, void* arg) {
  int r = 0;
  do r = ::ioctl(fd, request, arg);
  while (r == -1 && errno == EINTR);
  return r;
}

std::optional<PixelFormat> pixel_format_of(std::uint32_t fourcc) {
  switch (fourcc) {
    case V4L2_PIX_FMT_GREY: return PixelFormat::grey;
    case V4L2_PIX_FMT_YUYV: return PixelFormat::yuyv;
    case V4L2_PIX_FMT_MJPEG:
    case V4L2_PIX_FMT_JPEG: return PixelFormat::mjpeg;
    default: return std::nullopt;
  }
}

std::uint32_t fourcc_of(PixelFormat format) {
  switch (format) {
    case PixelFormat::grey: return V4L2_PIX_FMT_GREY;
    case PixelFormat::yuyv: return V4L2_PIX_FMT_YUYV;
    case PixelFormat::mjpeg: return V4L2_PIX_FMT_MJPEG;
  }
  return 0;
}

std::string fourcc_text(std::uint32_t fourcc) {
  std::string s;
  for (int i = 0; i < 4; ++i) {
    const char c = static_cast<char>((fourcc >> (8 * i)) & 0xff);
    s += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  }
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

namespace {

std::string text_of(const __u8* bytes, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(bytes), strnlen(reinterpret_cast<const char*>(bytes), size));
}

std::vector<double> rates_at(int fd, std::uint32_t fourcc, int width, int height) {
  std::vector<double> rates;
  v4l2_frmivalenum iv{};
  iv.pixel_format = fourcc;
  iv.width = static_cast<__u32>(width);
  iv.height = static_cast<__u32>(height);
  for (iv.index = 0; iv.index < 64 && xioctl(fd, VIDIOC_ENUM_FRAMEINTERVALS, &iv) == 0; ++iv.index) {
    if (iv.type == V4L2_FRMIVAL_TYPE_DISCRETE) {
      if (iv.discrete.numerator > 0) rates.push_back(double(iv.discrete.denominator) / iv.discrete.numerator);
    } else {  // a range: its fastest and slowest ends
      if (iv.stepwise.min.numerator > 0) rates.push_back(double(iv.stepwise.min.denominator) / iv.stepwise.min.numerator);
      if (iv.stepwise.max.numerator > 0) rates.push_back(double(iv.stepwise.max.denominator) / iv.stepwise.max.numerator);
      break;
    }
  }
  std::sort(rates.rbegin(), rates.rend());
  rates.erase(std::unique(rates.begin(), rates.end()), rates.end());
  return rates;
}

std::vector<CameraFormat> formats_of(int fd) {
  std::vector<CameraFormat> out;
  v4l2_fmtdesc fd_desc{};
  fd_desc.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  for (fd_desc.index = 0; fd_desc.index < 64 && xioctl(fd, VIDIOC_ENUM_FMT, &fd_desc) == 0; ++fd_desc.index) {
    CameraFormat f;
    f.fourcc = fd_desc.pixelformat;
    f.description = text_of(fd_desc.description, sizeof fd_desc.description);
    v4l2_frmsizeenum fs{};
    fs.pixel_format = f.fourcc;
    for (fs.index = 0; fs.index < 64 && xioctl(fd, VIDIOC_ENUM_FRAMESIZES, &fs) == 0; ++fs.index) {
      CameraSize size;
      if (fs.type == V4L2_FRMSIZE_TYPE_DISCRETE) {
        size.width = static_cast<int>(fs.discrete.width);
        size.height = static_cast<int>(fs.discrete.height);
      } else {
        size.width = static_cast<int>(fs.stepwise.max_width);
        size.height = static_cast<int>(fs.stepwise.max_height);
        size.stepwise = true;
      }
      size.rates_hz = rates_at(fd, f.fourcc, size.width, size.height);
      f.sizes.push_back(std::move(size));
      if (fs.type != V4L2_FRMSIZE_TYPE_DISCRETE) break;
    }
    out.push_back(std::move(f));
  }
  return out;
}

std::optional<std::string> control_text(int fd, std::uint32_t id, const char* name, const char* unit) {
  v4l2_queryctrl q{};
  q.id = id;
  if (xioctl(fd, VIDIOC_QUERYCTRL, &q) != 0 || (q.flags & V4L2_CTRL_FLAG_DISABLED)) return std::nullopt;
  v4l2_control c{};
  c.id = id;
  const bool has_value = xioctl(fd, VIDIOC_G_CTRL, &c) == 0;
  std::string s = fmt::format("{} {}..{}{}", name, q.minimum, q.maximum, unit);
  if (has_value) s += fmt::format(", now {}", c.value);
  return s;
}

std::vector<std::string> controls_of(int fd) {
  std::vector<std::string> out;
  if (auto s = control_text(fd, V4L2_CID_EXPOSURE_AUTO, "exposure_auto", " (1 = manual)")) out.push_back(*s);
  if (auto s = control_text(fd, V4L2_CID_EXPOSURE_ABSOLUTE, "exposure", " (100 µs)")) out.push_back(*s);
  if (auto s = control_text(fd, V4L2_CID_EXPOSURE_AUTO_PRIORITY, "exposure_auto_priority", "")) out.push_back(*s);
  if (auto s = control_text(fd, V4L2_CID_GAIN, "gain", "")) out.push_back(*s);
  return out;
}

//! The number in /dev/videoN, for ordering (video10 after video9).
int node_number(const std::string& name) {
  int n = 0;
  for (char c : name.substr(5)) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return 1 << 30;
    n = n * 10 + (c - '0');
  }
  return n;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

CameraScan scan_cameras(const std::string& dir, bool with_formats) {
  CameraScan scan;
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("video", 0) == 0 && name.size() > 5) names.push_back(name);
  }
  std::sort(names.begin(), names.end(),
            [](const std::string& a, const std::string& b) { return node_number(a) < node_number(b); });
  for (const std::string& name : names) {
    const std::string path = (std::filesystem::path(dir) / name).string();
    const int fd = ::open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
      if (scan.unreadable++ == 0) scan.first_error = open_error(path, errno, "video");
      continue;
    }
    v4l2_capability cap{};
    if (xioctl(fd, VIDIOC_QUERYCAP, &cap) == 0) {
      const std::uint32_t caps = (cap.capabilities & V4L2_CAP_DEVICE_CAPS) ? cap.device_caps : cap.capabilities;
      if ((caps & V4L2_CAP_VIDEO_CAPTURE) && (caps & V4L2_CAP_STREAMING)) {
        CameraInfo info;
        info.path = path;
        info.name = text_of(cap.card, sizeof cap.card);
        info.driver = text_of(cap.driver, sizeof cap.driver);
        info.bus = text_of(cap.bus_info, sizeof cap.bus_info);
        if (with_formats) {
          info.formats = formats_of(fd);
          info.controls = controls_of(fd);
        }
        scan.cameras.push_back(std::move(info));
      }
    }
    ::close(fd);
  }
  return scan;
}

Result<std::string, std::string> find_camera(const std::string& device, const std::string& dir) {
  if (device.find('/') != std::string::npos) return device;
  const CameraScan scan = scan_cameras(dir, false);
  const std::string want = lower(device);
  for (const CameraInfo& c : scan.cameras)
    if (device == kAutoCamera || lower(c.name).find(want) != std::string::npos) return c.path;
  std::string why = device == kAutoCamera ? fmt::format("no camera among {}/video*", dir)
                                          : fmt::format("no camera named like \"{}\" among {}/video*", device, dir);
  if (scan.unreadable > 0) why += fmt::format(" ({} could not be opened: {})", scan.unreadable, scan.first_error);
  return tl::unexpected(why);
}

}  // namespace mallet::input::camera
