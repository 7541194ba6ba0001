#include "app/bench/bench_latency_x11.hpp"

#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/extensions/XTest.h>
#include <fcntl.h>
#include <poll.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <stdexcept>

namespace mallet::app::latency {

void CloseDisplay::operator()(Display* display) const { XCloseDisplay(display); }

namespace {

//! Xlib's default error handler exits the process; a refused request (a window that just
//! went away, a box off the screen) must be an answer instead.
int ignore_x_error(Display*, XErrorEvent*) { return 0; }

Display* open_display(const std::string& name) {
  // The picture watch reads the screen on its own thread and connection, while the main
  // thread moves the pointer on another (libX11 ≥ 1.8 does this by default; older ones
  // need it before any other call).
  static const bool threads = XInitThreads() != 0;
  (void)threads;
  XSetErrorHandler(&ignore_x_error);
  Display* d = XOpenDisplay(name.c_str());
  if (!d) throw std::runtime_error("cannot connect to the bench's X server " + name);
  return d;
}

void sleep_until(Nanos t) {
  timespec ts{static_cast<time_t>(t / kNanosPerSecond), static_cast<long>(t % kNanosPerSecond)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

}  // namespace

VirtualDisplay::VirtualDisplay(int width, int height) {
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("bench latency: pipe failed");
  ChildOptions o;
  o.argv = {"Xvfb",      "-displayfd", std::to_string(fds[1]),
            "-screen",   "0",          std::to_string(width) + "x" + std::to_string(height) + "x24",
            "-nolisten", "tcp"};
  o.keep_fd = fds[1];
  o.env = {{"LD_PRELOAD", ""}};  // the sanitizer tests preload the Vulkan driver into the bench
  try {
    server_ = std::make_unique<Child>(std::move(o));
  } catch (...) {
    close(fds[0]);
    close(fds[1]);
    throw;
  }
  close(fds[1]);
  // Xvfb writes the display number and a newline once it accepts clients.
  std::string number;
  const Nanos deadline = monotonic_now() + 10 * kNanosPerSecond;
  while (monotonic_now() < deadline && number.find('\n') == std::string::npos) {
    pollfd p{fds[0], POLLIN, 0};
    if (poll(&p, 1, 100) <= 0) {
      if (!server_->running()) break;
      continue;
    }
    char buf[32];
    const ssize_t n = read(fds[0], buf, sizeof buf);
    if (n <= 0) break;
    number.append(buf, static_cast<std::size_t>(n));
  }
  close(fds[0]);
  const std::size_t nl = number.find('\n');
  if (nl == std::string::npos || nl == 0)
    throw std::runtime_error("Xvfb did not start within 10 s (" + server_->ended_how() + "):\n" + server_->tail(8));
  name_ = ":" + number.substr(0, nl);
}

FakePointer::FakePointer(const std::string& display) : display_(open_display(display)) {
  int event = 0, error = 0, major = 0, minor = 0;
  if (!XTestQueryExtension(display_.get(), &event, &error, &major, &minor))
    throw std::runtime_error("the X server " + display + " has no XTEST extension");
}

unsigned long FakePointer::window_of_size(int width, int height) {
  const Window root = DefaultRootWindow(display_.get());
  Window root_ret = 0, parent = 0, *children = nullptr;
  unsigned int n = 0;
  if (!XQueryTree(display_.get(), root, &root_ret, &parent, &children, &n)) return 0;
  Window found = 0;
  for (unsigned int i = 0; i < n && !found; ++i) {
    XWindowAttributes a;
    if (!XGetWindowAttributes(display_.get(), children[i], &a)) continue;
    if (a.map_state == IsViewable && a.width == width && a.height == height) found = children[i];
  }
  if (children) XFree(children);
  return found;
}

std::optional<PixelBox> FakePointer::find_window(int width, int height) {
  const Window window = window_of_size(width, height);
  if (!window) return std::nullopt;
  const Window root = DefaultRootWindow(display_.get());
  int x = 0, y = 0;
  Window child = 0;
  XTranslateCoordinates(display_.get(), window, root, 0, 0, &x, &y, &child);
  if (x != 0 || y != 0) {  // no window manager here: we may place it ourselves
    XMoveWindow(display_.get(), window, 0, 0);
    XSync(display_.get(), False);
    XTranslateCoordinates(display_.get(), window, root, 0, 0, &x, &y, &child);
  }
  return PixelBox{x, y, width, height};
}

bool FakePointer::resize_window(int width, int height, int to_width, int to_height) {
  const Window window = window_of_size(width, height);
  if (!window) return false;
  XResizeWindow(display_.get(), window, static_cast<unsigned>(to_width), static_cast<unsigned>(to_height));
  XSync(display_.get(), False);
  return true;
}

Nanos FakePointer::move_to(int x, int y) {
  XTestFakeMotionEvent(display_.get(), -1, x, y, CurrentTime);
  XFlush(display_.get());
  return monotonic_now();
}

void FakePointer::press_key(unsigned long keysym) {
  Display* d = display_.get();
  const KeyCode code = XKeysymToKeycode(d, static_cast<KeySym>(keysym));
  XTestFakeKeyEvent(d, code, True, CurrentTime);
  XTestFakeKeyEvent(d, code, False, CurrentTime);
  XFlush(d);
}

ScreenReader::ScreenReader(const std::string& display) : display_(open_display(display)) {}

bool ScreenReader::grab(const PixelBox& box, Grab& out) {
  out.sent = monotonic_now();
  Display* d = display_.get();
  XImage* image = XGetImage(d, DefaultRootWindow(d), box.x, box.y, static_cast<unsigned>(box.width),
                            static_cast<unsigned>(box.height), AllPlanes, ZPixmap);
  out.received = monotonic_now();
  if (!image) return false;
  out.rgb.resize(static_cast<std::size_t>(box.width * box.height));
  for (int y = 0; y < box.height; ++y)
    for (int x = 0; x < box.width; ++x)
      out.rgb[static_cast<std::size_t>(y * box.width + x)] =
          static_cast<std::uint32_t>(XGetPixel(image, x, y) & 0xffffff);
  XDestroyImage(image);
  return true;
}

std::optional<int> lowest_white_row(const Grab& g, const PixelBox& box) {
  for (int y = box.height - 1; y >= 0; --y)
    for (int x = 0; x < box.width; ++x) {
      const std::uint32_t p = g.rgb[static_cast<std::size_t>(y * box.width + x)];
      if (((p >> 16) & 0xff) >= kWhite && ((p >> 8) & 0xff) >= kWhite && (p & 0xff) >= kWhite) return box.y + y;
    }
  return std::nullopt;
}

PictureWatch::PictureWatch(const std::string& display, std::vector<PixelBox> strips, int tolerance_px)
    : strips_(std::move(strips)), tolerance_(tolerance_px), rest_rows_(new std::atomic<int>[strips_.size()]) {
  for (std::size_t i = 0; i < strips_.size(); ++i) rest_rows_[i].store(-1);
  thread_ = std::thread([this, display] { run(display); });
}

PictureWatch::~PictureWatch() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

void PictureWatch::run(std::string display) {
  try {
    ScreenReader reader(display);
    std::vector<Grab> grabs(strips_.size());
    std::vector<Nanos> previous_sent(strips_.size(), 0);
    std::vector<char> at_bar(strips_.size(), 0);
    Nanos next = monotonic_now();
    first_poll_.store(next);
    while (!stop_.load()) {
      for (std::size_t s = 0; s < strips_.size(); ++s) {
        Grab& g = grabs[s];
        if (!reader.grab(strips_[s], g)) continue;
        const int rest = rest_rows_[s].load();
        const std::optional<int> row = lowest_white_row(g, strips_[s]);
        const bool now_at_bar = rest >= 0 && row && *row >= rest - tolerance_;
        if (now_at_bar && !at_bar[s] && previous_sent[s] > 0) {
          std::lock_guard lock(mutex_);
          events_.push_back({static_cast<int>(s), (previous_sent[s] + g.received) / 2, g.received - previous_sent[s]});
        }
        at_bar[s] = now_at_bar;
        previous_sent[s] = g.sent;
      }
      polls_.fetch_add(1);
      last_poll_.store(monotonic_now());
      next += 1'000'000;  // ≈1 ms; a late poll does not make the next ones hurry
      const Nanos now = monotonic_now();
      if (next < now) next = now;
      sleep_until(next);
    }
  } catch (const std::exception& e) {
    std::lock_guard lock(mutex_);
    error_ = e.what();
  }
}

std::vector<PictureEvent> PictureWatch::take() {
  std::lock_guard lock(mutex_);
  if (!error_.empty()) throw std::runtime_error("picture watch: " + error_);
  std::vector<PictureEvent> out;
  out.swap(events_);
  return out;
}

double PictureWatch::mean_poll_ms() const {
  const std::uint64_t n = polls_.load();
  return n > 1 ? to_seconds(last_poll_.load() - first_poll_.load()) * 1e3 / static_cast<double>(n - 1) : 0.0;
}

}  // namespace mallet::app::latency
