#include "input/camera/v4l2_grabber.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/mman.h>
#include <unistd.h>

#include <linux/videodev2.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "input/camera/v4l2_node.hpp"

namespace mallet::input::camera {

namespace {

bool is_gone(int err) { return err == ENODEV || err == ENXIO || err == EIO || err == ENOENT; }

//! errno's words, and for EBUSY who may hold the camera (a V4L2 node streams to one program).
std::string why(int err) {
  return err == EBUSY ? std::string(kCameraInUse) : errno_text(err);
}

std::optional<v4l2_queryctrl> query(int fd, std::uint32_t id) {
  v4l2_queryctrl q{};
  q.id = id;
  if (xioctl(fd, VIDIOC_QUERYCTRL, &q) != 0 || (q.flags & V4L2_CTRL_FLAG_DISABLED)) return std::nullopt;
  return q;
}

std::optional<int> get_control(int fd, std::uint32_t id) {
  v4l2_control c{};
  c.id = id;
  if (xioctl(fd, VIDIOC_G_CTRL, &c) != 0) return std::nullopt;
  return c.value;
}

bool set_control(int fd, std::uint32_t id, int value) {
  v4l2_control c{};
  c.id = id;
  c.value = value;
  return xioctl(fd, VIDIOC_S_CTRL, &c) == 0;
}

//! The formats the camera offers for capture.
std::vector<std::uint32_t> offered(int fd) {
  std::vector<std::uint32_t> out;
  v4l2_fmtdesc d{};
  d.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  for (d.index = 0; d.index < 64 && xioctl(fd, VIDIOC_ENUM_FMT, &d) == 0; ++d.index) out.push_back(d.pixelformat);
  return out;
}

std::string offered_text(const std::vector<std::uint32_t>& codes) {
  std::string s;
  for (std::uint32_t c : codes) s += (s.empty() ? "" : ", ") + fourcc_text(c);
  return s.empty() ? "nothing" : s;
}

}  // namespace

V4l2Grabber::V4l2Grabber(CameraConfig config, std::string video_dir)
    : config_(std::move(config)), video_dir_(std::move(video_dir)) {
  wake_fd_ = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
}

V4l2Grabber::~V4l2Grabber() {
  close();
  if (wake_fd_ >= 0) ::close(wake_fd_);
}

Result<CameraMode, std::string> V4l2Grabber::open() {
  close();
  const Result<std::string, std::string> path = find_camera(config_.device, video_dir_);
  if (!path) return tl::unexpected(path.error());
  fd_ = ::open(path->c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) return tl::unexpected(open_error(*path, errno, "video"));
  Result<CameraMode, std::string> mode = negotiate(*path);
  if (!mode) {
    close();
    return mode;
  }
  mode_ = *mode;
  if (Result<void, std::string> started = start_streaming(*path); !started) {
    close();
    return tl::unexpected(started.error());
  }
  return mode_;
}

Result<CameraMode, std::string> V4l2Grabber::negotiate(const std::string& path) {
  CameraMode mode;
  mode.device = path;
  v4l2_capability cap{};
  if (xioctl(fd_, VIDIOC_QUERYCAP, &cap) != 0)
    return tl::unexpected(fmt::format("{}: not a V4L2 device ({})", path, errno_text(errno)));
  const std::uint32_t caps = (cap.capabilities & V4L2_CAP_DEVICE_CAPS) ? cap.device_caps : cap.capabilities;
  if (!(caps & V4L2_CAP_VIDEO_CAPTURE) || !(caps & V4L2_CAP_STREAMING))
    return tl::unexpected(fmt::format("{}: not a camera that streams (no video capture with streaming I/O)", path));
  mode.name = reinterpret_cast<const char*>(cap.card);
  mode.driver = reinterpret_cast<const char*>(cap.driver);

  // The format: the one asked for, or the fastest to read that the camera offers.
  const std::vector<std::uint32_t> codes = offered(fd_);
  std::optional<PixelFormat> chosen;
  if (config_.format == "auto") {
    for (PixelFormat f : {PixelFormat::grey, PixelFormat::yuyv, PixelFormat::mjpeg})
      if (!chosen && std::find(codes.begin(), codes.end(), fourcc_of(f)) != codes.end()) chosen = f;
    if (!chosen && std::find(codes.begin(), codes.end(), V4L2_PIX_FMT_JPEG) != codes.end()) chosen = PixelFormat::mjpeg;
    if (!chosen)
      return tl::unexpected(fmt::format("{}: offers {}; Mallet reads GREY, YUYV or MJPG", path, offered_text(codes)));
  } else {
    chosen = value_named(kPixelFormatNames, config_.format);
    if (!chosen || std::find(codes.begin(), codes.end(), fourcc_of(*chosen)) == codes.end())
      return tl::unexpected(fmt::format("{}: [camera] format = \"{}\", but the camera offers {}", path, config_.format,
                                        offered_text(codes)));
  }
  v4l2_format fmt{};
  fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  fmt.fmt.pix.width = static_cast<__u32>(config_.width);
  fmt.fmt.pix.height = static_cast<__u32>(config_.height);
  fmt.fmt.pix.pixelformat = fourcc_of(*chosen);
  fmt.fmt.pix.field = V4L2_FIELD_NONE;
  if (xioctl(fd_, VIDIOC_S_FMT, &fmt) != 0)
    return tl::unexpected(fmt::format("{}: the camera refused {} {}x{} ({})", path, name_in(kPixelFormatNames, *chosen),
                                      config_.width, config_.height, why(errno)));
  const std::optional<PixelFormat> got = pixel_format_of(fmt.fmt.pix.pixelformat);
  if (!got)
    return tl::unexpected(fmt::format("{}: asked for {}, the driver gave {}", path, name_in(kPixelFormatNames, *chosen),
                                      fourcc_text(fmt.fmt.pix.pixelformat)));
  mode.format = *got;
  mode.width = static_cast<int>(fmt.fmt.pix.width);
  mode.height = static_cast<int>(fmt.fmt.pix.height);
  bytes_per_line_ = fmt.fmt.pix.bytesperline;
  if (mode.width != config_.width || mode.height != config_.height)
    mode.notes.push_back(fmt::format("asked for {}x{}, the camera gives {}x{}", config_.width, config_.height,
                                     mode.width, mode.height));

  // The frame interval.
  v4l2_streamparm parm{};
  parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  if (xioctl(fd_, VIDIOC_G_PARM, &parm) == 0 && (parm.parm.capture.capability & V4L2_CAP_TIMEPERFRAME)) {
    parm.parm.capture.timeperframe.numerator = 1000;
    parm.parm.capture.timeperframe.denominator = static_cast<__u32>(std::lround(config_.rate_hz * 1000));
    if (xioctl(fd_, VIDIOC_S_PARM, &parm) != 0)
      mode.notes.push_back(fmt::format("the camera refused {:g} frames a second ({})", config_.rate_hz, errno_text(errno)));
    const v4l2_fract& t = parm.parm.capture.timeperframe;
    if (t.numerator > 0) mode.rate_hz = double(t.denominator) / t.numerator;
    if (std::fabs(mode.rate_hz - config_.rate_hz) > 0.01 * config_.rate_hz)
      mode.notes.push_back(fmt::format("asked for {:g} frames a second, the camera gives {:.4g}", config_.rate_hz,
                                       mode.rate_hz));
  } else {
    mode.notes.push_back("the camera does not let its frame rate be set");
  }
  set_controls(mode);
  return mode;
}

void V4l2Grabber::set_controls(CameraMode& mode) {
  if (config_.exposure_us > 0) {
    const std::optional<v4l2_queryctrl> abs = query(fd_, V4L2_CID_EXPOSURE_ABSOLUTE);
    if (!abs) {
      mode.notes.push_back("the camera has no exposure control: its own automatic exposure stays");
    } else {
      if (query(fd_, V4L2_CID_EXPOSURE_AUTO) && !set_control(fd_, V4L2_CID_EXPOSURE_AUTO, V4L2_EXPOSURE_MANUAL))
        mode.notes.push_back("the camera would not switch to manual exposure (" + errno_text(errno) + ")");
      // A UVC camera may otherwise stretch its frames for a longer exposure in a dim room.
      if (query(fd_, V4L2_CID_EXPOSURE_AUTO_PRIORITY)) set_control(fd_, V4L2_CID_EXPOSURE_AUTO_PRIORITY, 0);
      const int units = std::clamp((config_.exposure_us + 50) / 100, abs->minimum, abs->maximum);  // 100 µs units
      if (!set_control(fd_, V4L2_CID_EXPOSURE_ABSOLUTE, units))
        mode.notes.push_back("the camera refused the exposure (" + errno_text(errno) + ")");
      if (units * 100 != config_.exposure_us)
        mode.notes.push_back(fmt::format("exposure {} µs asked, {} µs set (the camera's steps are 100 µs, {}..{})",
                                         config_.exposure_us, units * 100, abs->minimum * 100, abs->maximum * 100));
    }
  }
  if (const std::optional<int> auto_mode = get_control(fd_, V4L2_CID_EXPOSURE_AUTO))
    mode.exposure_manual = *auto_mode == V4L2_EXPOSURE_MANUAL;
  if (const std::optional<int> units = get_control(fd_, V4L2_CID_EXPOSURE_ABSOLUTE)) mode.exposure_us = *units * 100;
  if (config_.gain >= 0) {
    if (const std::optional<v4l2_queryctrl> g = query(fd_, V4L2_CID_GAIN)) {
      const int value = std::clamp(config_.gain, g->minimum, g->maximum);
      if (!set_control(fd_, V4L2_CID_GAIN, value)) mode.notes.push_back("the camera refused the gain (" + errno_text(errno) + ")");
      else if (value != config_.gain)
        mode.notes.push_back(fmt::format("gain {} asked, {} set (the camera's range is {}..{})", config_.gain, value,
                                         g->minimum, g->maximum));
    } else {
      mode.notes.push_back("the camera has no gain control");
    }
  }
  mode.gain = get_control(fd_, V4L2_CID_GAIN).value_or(-1);
  // The correction to mid-exposure uses the exposure in force; an automatic one is read now
  // (it may change later: the stamps then err by half the change).
  exposure_ns_ = static_cast<Nanos>(mode.exposure_us) * 1000;
}

Result<void, std::string> V4l2Grabber::start_streaming(const std::string& path) {
  v4l2_requestbuffers req{};
  req.count = kBuffers;
  req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  req.memory = V4L2_MEMORY_MMAP;
  if (xioctl(fd_, VIDIOC_REQBUFS, &req) != 0 || req.count < 2)
    return tl::unexpected(fmt::format("{}: no memory-mapped buffers ({})", path, why(errno)));
  for (mapped_ = 0; mapped_ < std::min<std::size_t>(req.count, kBuffers); ++mapped_) {
    v4l2_buffer b{};
    b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    b.memory = V4L2_MEMORY_MMAP;
    b.index = static_cast<__u32>(mapped_);
    if (xioctl(fd_, VIDIOC_QUERYBUF, &b) != 0)
      return tl::unexpected(fmt::format("{}: buffer {}: {}", path, mapped_, errno_text(errno)));
    void* start = ::mmap(nullptr, b.length, PROT_READ | PROT_WRITE, MAP_SHARED, fd_, b.m.offset);
    if (start == MAP_FAILED) return tl::unexpected(fmt::format("{}: mmap: {}", path, errno_text(errno)));
    buffers_[mapped_] = {start, b.length};
    if (xioctl(fd_, VIDIOC_QBUF, &b) != 0)
      return tl::unexpected(fmt::format("{}: queueing buffer {}: {}", path, mapped_, errno_text(errno)));
  }
  v4l2_buf_type type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  if (xioctl(fd_, VIDIOC_STREAMON, &type) != 0)
    return tl::unexpected(fmt::format("{}: streaming would not start ({})", path, why(errno)));
  return {};
}

void V4l2Grabber::requeue() {
  if (held_ < 0 || fd_ < 0) return;
  v4l2_buffer b{};
  b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  b.memory = V4L2_MEMORY_MMAP;
  b.index = static_cast<__u32>(held_);
  xioctl(fd_, VIDIOC_QBUF, &b);
  held_ = -1;
}

Result<bool, GrabError> V4l2Grabber::next(int timeout_ms, CameraFrame& frame) {
  if (fd_ < 0) return tl::unexpected(GrabError{"the camera is not open", true});
  requeue();
  pollfd fds[2] = {{fd_, POLLIN, 0}, {wake_fd_, POLLIN, 0}};
  const int n = ::poll(fds, wake_fd_ >= 0 ? 2 : 1, timeout_ms);
  if (n < 0) {
    if (errno == EINTR) return false;
    return tl::unexpected(GrabError{"poll: " + errno_text(errno), false});
  }
  if (wake_fd_ >= 0 && (fds[1].revents & POLLIN)) {
    std::uint64_t count = 0;
    [[maybe_unused]] const ssize_t r = ::read(wake_fd_, &count, sizeof count);
    return false;
  }
  if (n == 0) return false;
  v4l2_buffer b{};
  b.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  b.memory = V4L2_MEMORY_MMAP;
  if (xioctl(fd_, VIDIOC_DQBUF, &b) != 0) {
    const int err = errno;
    if (err == EAGAIN) {
      if (fds[0].revents & (POLLERR | POLLHUP)) return tl::unexpected(GrabError{mode_.device + ": the camera went away", true});
      return false;
    }
    return tl::unexpected(GrabError{fmt::format("{}: {}", mode_.device, errno_text(err)), is_gone(err)});
  }
  held_ = static_cast<int>(b.index);
  if (b.index >= mapped_ || (b.flags & V4L2_BUF_FLAG_ERROR)) return false;  // a damaged frame: the next one
  const bool monotonic = (b.flags & V4L2_BUF_FLAG_TIMESTAMP_MASK) == V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC;
  const StampSource source = !monotonic ? StampSource::read_time
                             : (b.flags & V4L2_BUF_FLAG_TSTAMP_SRC_MASK) == V4L2_BUF_FLAG_TSTAMP_SRC_SOE
                                 ? StampSource::start_of_exposure
                                 : StampSource::end_of_exposure;
  const Nanos stamp = monotonic ? Nanos(b.timestamp.tv_sec) * kNanosPerSecond + Nanos(b.timestamp.tv_usec) * 1000
                                : monotonic_now();
  if (mode_.stamping.empty()) mode_.stamping = describe(source);
  frame.t_ns = mid_exposure_ns(stamp, source, exposure_ns_);
  frame.sequence = b.sequence;
  frame.width = mode_.width;
  frame.height = mode_.height;
  frame.format = mode_.format;
  frame.bytes_per_line = bytes_per_line_;
  frame.bytes = {static_cast<const std::uint8_t*>(buffers_[b.index].start),
                 std::min<std::size_t>(b.bytesused, buffers_[b.index].length)};
  return true;
}

void V4l2Grabber::close() {
  if (fd_ >= 0) {
    v4l2_buf_type type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    xioctl(fd_, VIDIOC_STREAMOFF, &type);
  }
  for (std::size_t i = 0; i < mapped_; ++i)
    if (buffers_[i].start) ::munmap(buffers_[i].start, buffers_[i].length);
  buffers_ = {};
  mapped_ = 0;
  held_ = -1;
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void V4l2Grabber::wake() {
  const std::uint64_t one = 1;
  if (wake_fd_ >= 0) {
    [[maybe_unused]] const ssize_t r = ::write(wake_fd_, &one, sizeof one);
  }
}

}  // namespace mallet::input::camera
