#pragma once
// A scriptable stand-in for libevdev: fake_libevdev.cpp defines the libevdev_* functions
// EvdevMouse calls, and evdev_mouse_tests links it instead of the real library. This machine
// has no mouse and no /dev/uinput to make one, so the reading thread (poll, SYN_DROPPED
// resync, the device going away and coming back, stop) is tested with events scripted here
// on a real character device (/dev/null: open() and fstat() work, poll() is always ready).
#include <linux/input.h>

#include <string>

namespace fake_libevdev {

struct Device {
  std::string name = "Fake Mouse";
  bool relative = true;        //!< REL_X + REL_Y
  bool left_button = true;     //!< BTN_LEFT
  bool absolute = false;       //!< ABS_X + ABS_Y in 0..1000, at (250, 750)
  int set_clock_result = 0;    //!< what libevdev_set_clock_id answers (-EINVAL: the old-kernel path)
};

//! Forgets every event and count; the device is present and as given.
void reset(Device device = {});
//! While absent, libevdev_new_from_fd fails with -ENODEV (the node is gone).
void set_present(bool present);
//! The next libevdev_next_event in normal mode returns it (status SUCCESS).
void push(const input_event& event);
//! libevdev's view of a SYN_DROPPED: status SYNC with the SYN_DROPPED event, then in sync
//! mode nothing (a mouse's relative motion has no state to sync).
void push_dropped(const input_event& event);
//! The next libevdev_next_event returns -`error_number` (ENODEV: unplugged).
void push_error(int error_number);
//! Events not yet read by the reader.
int pending();
//! libevdev handles made and freed so far; the clock id last asked for (-1 none).
int created();
int freed();
int clock_id();

}  // namespace fake_libevdev
