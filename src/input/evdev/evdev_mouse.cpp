#include "input/evdev/evdev_mouse.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <system_error>

#include <libevdev/libevdev.h>

#include "input/device_errors.hpp"

namespace mallet::input::evdev {

//! An open event node: its fd and libevdev handle, and what open() learnt about it.
class EvdevNode {
 public:
  EvdevNode(int fd, libevdev* dev) : fd_(fd), dev_(dev) {}
  ~EvdevNode() {
    libevdev_free(dev_);
    ::close(fd_);
  }
  EvdevNode(const EvdevNode&) = delete;
  EvdevNode& operator=(const EvdevNode&) = delete;

  int fd() const { return fd_; }
  libevdev* dev() const { return dev_; }

  EvdevDeviceInfo info;
  bool absolute = false;
  bool clock_mapped = false;
  Nanos clock_offset_ns = 0;
  AbsAxisRange abs_x, abs_y;  //!< {0, 0} when the node has no such axis

 private:
  int fd_;
  libevdev* dev_;
};

namespace {

std::string file_kind(mode_t mode) {
  if (S_ISREG(mode)) return "a regular file";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a pipe";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISBLK(mode)) return "a block device";
  return "not a character device";
}

//! Why a node could not be read from: one line a person can act on.
struct NodeError {
  std::string message;
  bool unreadable = false;  //!< open() itself failed (permissions, a vanished node), not the kind of node
};
using NodeResult = Result<std::unique_ptr<EvdevNode>, NodeError>;

tl::unexpected<NodeError> node_error(std::string message, bool unreadable = false) {
  return tl::unexpected(NodeError{std::move(message), unreadable});
}

//! Opens `path` non-blocking (libevdev_next_event then answers -EAGAIN instead of waiting,
//! and the thread waits in poll(), where stop() can wake it). Checks it is an evdev node.
NodeResult open_evdev(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return node_error(open_error(path, errno, "input"), true);
  struct stat st {};
  const bool stat_ok = ::fstat(fd, &st) == 0;
  if (!stat_ok || !S_ISCHR(st.st_mode)) {
    const std::string kind = stat_ok ? file_kind(st.st_mode) : errno_text(errno);
    ::close(fd);
    return node_error(path + ": not an input event device (" + kind + "); give a /dev/input/event* node or \"auto\"");
  }
  libevdev* dev = nullptr;
  const int rc = libevdev_new_from_fd(fd, &dev);
  if (rc < 0) {
    ::close(fd);
    return node_error(path + ": not an input event device (" + errno_text(-rc) + ")");
  }
  auto node = std::make_unique<EvdevNode>(fd, dev);
  node->info.path = path;
  const char* name = libevdev_get_name(dev);
  node->info.name = name ? name : "";
  return node;
}

bool is_mouse(libevdev* dev) {
  return libevdev_has_event_code(dev, EV_REL, REL_X) && libevdev_has_event_code(dev, EV_REL, REL_Y) &&
         libevdev_has_event_code(dev, EV_KEY, BTN_LEFT);
}

Nanos clock_now(clockid_t clock) {
  timespec ts{};
  ::clock_gettime(clock, &ts);
  return static_cast<Nanos>(ts.tv_sec) * kNanosPerSecond + ts.tv_nsec;
}

//! Opens a node to read a pointer from: relative (REL_X + REL_Y) or absolute (ABS_X +
//! ABS_Y), stamped on CLOCK_MONOTONIC.
NodeResult open_pointer(const std::string& path) {
  NodeResult result = open_evdev(path);
  if (!result) return result;
  EvdevNode& node = **result;
  libevdev* dev = node.dev();
  const bool relative = libevdev_has_event_code(dev, EV_REL, REL_X) && libevdev_has_event_code(dev, EV_REL, REL_Y);
  const bool absolute = libevdev_has_event_code(dev, EV_ABS, ABS_X) && libevdev_has_event_code(dev, EV_ABS, ABS_Y);
  if (!relative && !absolute) {
    return node_error(path + " (" + node.info.name +
                      "): not a pointer (it has neither REL_X + REL_Y nor ABS_X + ABS_Y)");
  }
  node.absolute = !relative;
  if (absolute) {
    const input_absinfo* x = libevdev_get_abs_info(dev, ABS_X);
    const input_absinfo* y = libevdev_get_abs_info(dev, ABS_Y);
    if (x) node.abs_x = {x->minimum, x->maximum};
    if (y) node.abs_y = {y->minimum, y->maximum};
  }
  // The kernel stamps evdev events on CLOCK_REALTIME unless told otherwise; REALTIME jumps
  // with NTP and the operator's clock. Kernels before 3.4 cannot switch: map REALTIME onto
  // the monotonic clock with an offset measured now (wrong by any later jump of the wall
  // clock, which status() makes visible).
  if (libevdev_set_clock_id(dev, CLOCK_MONOTONIC) != 0) {
    node.clock_mapped = true;
    node.clock_offset_ns = clock_now(CLOCK_MONOTONIC) - clock_now(CLOCK_REALTIME);
  }
  return result;
}

NodeResult open_auto(const std::filesystem::path& dir) {
  const MouseScan scan = scan_mice(dir);
  if (scan.mice.empty()) {
    std::string error = "no mouse among " + (dir / "event*").string();
    if (scan.unreadable > 0) {
      error += " (" + std::to_string(scan.unreadable) + " event node" + (scan.unreadable == 1 ? "" : "s") +
               " could not be opened, first " + scan.first_error + ")";
      if (scan.first_error.find("'input' group") == std::string::npos &&
          (scan.first_error.find("denied") != std::string::npos)) {
        error += "; is the user in the 'input' group?";
      }
    }
    return node_error(error);
  }
  return open_pointer(scan.mice.front().path);
}

//! `spec`: a node's path, or "auto" (the first mouse in `dir`).
NodeResult open_spec(const std::string& spec, const std::filesystem::path& dir) {
  return spec == kAutoDevice ? open_auto(dir) : open_pointer(spec);
}

//! The number of "eventN", or -1 for any other name.
long event_number(const std::string& name) {
  if (!name.starts_with("event") || name.size() == 5 || name.size() > 14) return -1;
  long n = 0;
  for (std::size_t i = 5; i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9') return -1;
    n = n * 10 + (name[i] - '0');
  }
  return n;
}

std::string seconds_text(Nanos ns) {
  const double s = to_seconds(ns);
  std::string text = std::to_string(s);
  text.erase(text.find_last_not_of('0') + 1);
  if (text.back() == '.') text.pop_back();
  return text + " s";
}

}  // namespace

MouseScan scan_mice(const std::filesystem::path& dir) {
  MouseScan scan;
  std::vector<std::pair<long, std::filesystem::path>> nodes;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const long n = event_number(it->path().filename().string());
    if (n >= 0) nodes.emplace_back(n, it->path());
  }
  std::sort(nodes.begin(), nodes.end());
  for (const auto& [n, path] : nodes) {
    const NodeResult r = open_evdev(path.string());
    if (!r && r.error().unreadable && scan.unreadable++ == 0) scan.first_error = r.error().message;
    if (r && is_mouse((*r)->dev())) scan.mice.push_back((*r)->info);
  }
  return scan;
}

EvdevOpenResult EvdevMouse::open(const std::string& device, EvdevMouseConfig config) {
  if (config.screen_width_px <= 0 || config.screen_height_px <= 0) {
    return refused("the screen size must be > 0 pixels, got " + std::to_string(config.screen_width_px) + "x" +
                   std::to_string(config.screen_height_px));
  }
  if (!std::isfinite(config.speed_px_per_count) || config.speed_px_per_count <= 0)
    return refused("speed_px_per_count must be > 0, got " + std::to_string(config.speed_px_per_count));
  config.reopen_interval_ns = std::max<Nanos>(config.reopen_interval_ns, 1'000'000);
  config.poll_timeout_ms = std::clamp(config.poll_timeout_ms, 1, 1000);
  const std::string spec = device.empty() ? kAutoDevice : device;
  NodeResult opened = open_spec(spec, config.search_dir);
  if (!opened) return refused(opened.error().message);
  std::unique_ptr<EvdevMouse> mouse(new EvdevMouse(spec, std::move(config), std::move(*opened)));
  if (mouse->wake_fd_ < 0) return refused("cannot create an eventfd for the mouse's reading thread");
  return mouse;
}

EvdevMouse::EvdevMouse(std::string spec, EvdevMouseConfig config, std::unique_ptr<EvdevNode> node)
    : spec_(std::move(spec)), config_(std::move(config)), wake_fd_(::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC)) {
  decoder_.set_screen(config_.screen_width_px, config_.screen_height_px);
  decoder_.set_speed(config_.speed_px_per_count);
  attach(std::move(node));
}

EvdevMouse::~EvdevMouse() {
  stop();
  if (wake_fd_ >= 0) ::close(wake_fd_);
}

void EvdevMouse::start(PointerSink sink) {
  if (thread_.joinable()) return;
  stop_.store(false);
  thread_ = std::thread([this, sink = std::move(sink)] { run(sink); });
}

void EvdevMouse::stop() {
  if (!thread_.joinable()) return;
  stop_.store(true);
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t written = ::write(wake_fd_, &one, sizeof one);
  thread_.join();
  std::uint64_t count = 0;  // reset the eventfd, so a later start() does not wake at once
  [[maybe_unused]] const ssize_t got = ::read(wake_fd_, &count, sizeof count);
}

std::string EvdevMouse::describe() const {
  std::lock_guard lock(mutex_);
  const EvdevDeviceInfo& d = status_.device;
  return std::string(status_.absolute ? "pointer" : "mouse") + " via evdev " + d.path + " (" + d.name +
         (status_.absolute ? ", absolute)" : ")");
}

EvdevMouseStatus EvdevMouse::status() const {
  std::lock_guard lock(mutex_);
  return status_;
}

void EvdevMouse::warp(double x, double y) {
  {
    std::lock_guard lock(mutex_);
    warp_request_.emplace(x, y);
  }
  requests_.store(true, std::memory_order_release);
}

void EvdevMouse::set_screen(int width_px, int height_px) {
  {
    std::lock_guard lock(mutex_);
    screen_request_.emplace(width_px, height_px);
  }
  requests_.store(true, std::memory_order_release);
}

void EvdevMouse::apply_requests() {
  std::optional<std::pair<double, double>> warp;
  std::optional<std::pair<int, int>> screen;
  {
    std::lock_guard lock(mutex_);
    warp.swap(warp_request_);
    screen.swap(screen_request_);
  }
  if (screen) decoder_.set_screen(screen->first, screen->second);
  if (warp) decoder_.warp(warp->first, warp->second);
}

void EvdevMouse::attach(std::unique_ptr<EvdevNode> node) {
  node_ = std::move(node);
  decoder_.resynced();
  decoder_.set_clock_offset(node_->clock_offset_ns);
  decoder_.set_abs_range(ABS_X, node_->abs_x);
  decoder_.set_abs_range(ABS_Y, node_->abs_y);
  if (node_->absolute) {  // a touchscreen knows where it is before it is touched again
    const input_absinfo* x = libevdev_get_abs_info(node_->dev(), ABS_X);
    const input_absinfo* y = libevdev_get_abs_info(node_->dev(), ABS_Y);
    if (x && y && x->maximum > x->minimum && y->maximum > y->minimum) {
      decoder_.warp(static_cast<double>(x->value - x->minimum) / (x->maximum - x->minimum),
                    static_cast<double>(y->value - y->minimum) / (y->maximum - y->minimum));
    }
  }
  problem_.clear();
  publish(true);
}

void EvdevMouse::detach(const std::string& why) {
  node_.reset();
  problem_ = why + "; trying to open it again every " + seconds_text(config_.reopen_interval_ns);
  publish(true);
}

void EvdevMouse::publish(bool force_strings) {
  const double rate = rate_.rate_hz(monotonic_now());
  rate_hz_.store(rate, std::memory_order_relaxed);
  std::lock_guard lock(mutex_);
  status_.connected = node_ != nullptr;
  status_.counters = decoder_.counters();
  status_.rate_hz = rate;
  status_.reconnects = reconnects_;
  if (force_strings) {
    if (node_) {
      status_.device = node_->info;
      status_.absolute = node_->absolute;
      status_.clock_mapped = node_->clock_mapped;
    }
    status_.problem = problem_;
  }
}

void EvdevMouse::wait_for_wake(int timeout_ms) const {
  pollfd wake{wake_fd_, POLLIN, 0};
  ::poll(&wake, 1, timeout_ms);
}

Check EvdevMouse::read_events(std::vector<PointerSample>& batch) {
  // Bounded, so that a flood of events cannot keep stop() waiting; the rest is read at the
  // next wake-up (poll() answers at once while events are pending).
  constexpr int kMaxEventsPerWake = 4096;
  libevdev* dev = node_->dev();
  const auto take = [&](const input_event& event) {
    if (const auto sample = decoder_.feed(event)) batch.push_back(*sample);
  };
  for (int i = 0; i < kMaxEventsPerWake; ++i) {
    input_event event{};
    int rc = libevdev_next_event(dev, LIBEVDEV_READ_FLAG_NORMAL, &event);
    if (rc == LIBEVDEV_READ_STATUS_SYNC) {
      // SYN_DROPPED: count it and drop the partial frame. libevdev has discarded the stale
      // events itself and now hands over the device's current state as one frame (for a
      // mouse: buttons only, relative motion has no state), which the decoder takes.
      take(event);
      decoder_.resynced();
      while ((rc = libevdev_next_event(dev, LIBEVDEV_READ_FLAG_SYNC, &event)) == LIBEVDEV_READ_STATUS_SYNC) {
        take(event);
      }
      if (rc == -EAGAIN || rc >= 0) continue;
    }
    if (rc == LIBEVDEV_READ_STATUS_SUCCESS) {
      take(event);
      continue;
    }
    if (rc == -EAGAIN) return {};
    if (rc == -EINTR) continue;
    return refused(node_->info.path + ": the device went away (" + errno_text(-rc) + ")");
  }
  return {};
}

void EvdevMouse::run(PointerSink sink) {
  try {
    std::vector<PointerSample> batch;
    batch.reserve(1024);
    Nanos next_attempt_ns = 0;
    std::string lost;  // why the device went away, kept while reopening fails
    while (!stop_.load(std::memory_order_acquire)) {
      if (requests_.exchange(false, std::memory_order_acquire)) apply_requests();
      if (!node_) {
        const Nanos now = monotonic_now();
        if (now >= next_attempt_ns) {
          NodeResult opened = open_spec(spec_, config_.search_dir);
          if (opened) {
            ++reconnects_;
            attach(std::move(*opened));
            continue;
          }
          next_attempt_ns = now + config_.reopen_interval_ns;
          detach(lost + " (last attempt: " + opened.error().message + ")");
        }
        const Nanos wait_ns = std::max<Nanos>(next_attempt_ns - now, 0);
        wait_for_wake(static_cast<int>(std::min<Nanos>(wait_ns / 1'000'000 + 1, config_.poll_timeout_ms)));
        publish(false);
        continue;
      }
      pollfd fds[2] = {{node_->fd(), POLLIN, 0}, {wake_fd_, POLLIN, 0}};
      const int ready = ::poll(fds, 2, config_.poll_timeout_ms);
      if (ready > 0 && fds[0].revents != 0) {
        const Check alive = read_events(batch);
        if (!batch.empty()) {
          for (const PointerSample& sample : batch) rate_.add(sample.t_ns);
          sink(batch);
          batch.clear();
        }
        if (!alive) {
          lost = alive.error();
          detach(lost);
          next_attempt_ns = monotonic_now() + config_.reopen_interval_ns;
        }
      }
      publish(false);
    }
  } catch (const std::exception& e) {
    // Nothing may cross the thread: a throwing sink (against its contract) or an allocation
    // failure ends the reading, visibly.
    node_.reset();
    problem_ = std::string("the mouse's reading thread stopped: ") + e.what();
    publish(true);
  }
}

}  // namespace mallet::input::evdev
