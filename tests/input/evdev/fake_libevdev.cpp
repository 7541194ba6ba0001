#include "fake_libevdev.hpp"

#include <cerrno>
#include <chrono>
#include <deque>
#include <mutex>
#include <thread>

#include <libevdev/libevdev.h>

namespace fake_libevdev {
namespace {

struct Step {
  int status = LIBEVDEV_READ_STATUS_SUCCESS;  // or SYNC, or -errno
  input_event event{};
};

struct State {
  std::mutex mutex;
  Device device;
  bool present = true;
  std::deque<Step> steps;
  int created = 0;
  int freed = 0;
  int clock_id = -1;
  input_absinfo abs_x{250, 0, 1000, 0, 0, 0};
  input_absinfo abs_y{750, 0, 1000, 0, 0, 0};
};

State& state() {
  static State s;
  return s;
}

}  // namespace

void reset(Device device) {
  State& s = state();
  std::lock_guard lock(s.mutex);
  s.device = std::move(device);
  s.present = true;
  s.steps.clear();
  s.created = s.freed = 0;
  s.clock_id = -1;
}

void set_present(bool present) {
  std::lock_guard lock(state().mutex);
  state().present = present;
}

void push(const input_event& event) {
  std::lock_guard lock(state().mutex);
  state().steps.push_back({LIBEVDEV_READ_STATUS_SUCCESS, event});
}

void push_dropped(const input_event& event) {
  std::lock_guard lock(state().mutex);
  state().steps.push_back({LIBEVDEV_READ_STATUS_SYNC, event});
}

void push_error(int error_number) {
  std::lock_guard lock(state().mutex);
  state().steps.push_back({-error_number, {}});
}

int pending() {
  std::lock_guard lock(state().mutex);
  return static_cast<int>(state().steps.size());
}

int created() {
  std::lock_guard lock(state().mutex);
  return state().created;
}

int freed() {
  std::lock_guard lock(state().mutex);
  return state().freed;
}

int clock_id() {
  std::lock_guard lock(state().mutex);
  return state().clock_id;
}

}  // namespace fake_libevdev

using fake_libevdev::state;

// The handle only needs an address.
struct libevdev {
  int fd = -1;
};

extern "C" {

int libevdev_new_from_fd(int fd, struct libevdev** dev) {
  std::lock_guard lock(state().mutex);
  if (!state().present) return -ENODEV;
  *dev = new libevdev{fd};
  ++state().created;
  return 0;
}

void libevdev_free(struct libevdev* dev) {
  if (!dev) return;
  std::lock_guard lock(state().mutex);
  ++state().freed;
  delete dev;
}

const char* libevdev_get_name(const struct libevdev*) {
  std::lock_guard lock(state().mutex);
  return state().device.name.c_str();
}

int libevdev_has_event_code(const struct libevdev*, unsigned int type, unsigned int code) {
  std::lock_guard lock(state().mutex);
  const fake_libevdev::Device& d = state().device;
  if (type == EV_REL && (code == REL_X || code == REL_Y)) return d.relative;
  if (type == EV_ABS && (code == ABS_X || code == ABS_Y)) return d.absolute;
  if (type == EV_KEY && code == BTN_LEFT) return d.left_button;
  return 0;
}

const struct input_absinfo* libevdev_get_abs_info(const struct libevdev*, unsigned int code) {
  std::lock_guard lock(state().mutex);
  if (!state().device.absolute) return nullptr;
  if (code == ABS_X) return &state().abs_x;
  if (code == ABS_Y) return &state().abs_y;
  return nullptr;
}

int libevdev_set_clock_id(struct libevdev*, int clockid) {
  std::lock_guard lock(state().mutex);
  state().clock_id = clockid;
  return state().device.set_clock_result;
}

int libevdev_next_event(struct libevdev*, unsigned int flags, struct input_event* ev) {
  {
    std::lock_guard lock(state().mutex);
    auto& steps = state().steps;
    // Sync mode: nothing to sync for a mouse (relative motion has no state).
    if (!(flags & LIBEVDEV_READ_FLAG_SYNC) && !steps.empty()) {
      const fake_libevdev::Step step = steps.front();
      steps.pop_front();
      *ev = step.event;
      return step.status;
    }
  }
  // poll() on /dev/null is always ready: a short nap keeps the idle reader from spinning hard.
  if (!(flags & LIBEVDEV_READ_FLAG_SYNC)) std::this_thread::sleep_for(std::chrono::microseconds(200));
  return -EAGAIN;
}

}  // extern "C"
