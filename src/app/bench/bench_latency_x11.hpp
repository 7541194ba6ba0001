#pragma once
// The window-system side of `mallet bench latency`: a virtual X server of the bench's own
// (Xvfb), a hand that moves the X pointer (XTest, as a real mouse's events would arrive),
// and an eye on what the X server shows (XGetImage of a few pixels, polled).
//
// The kiosk under test is an ordinary X client of that server: the pointer events it reads
// are the ones injected here, and what it presents lands in the server's framebuffer,
// which is what a display would scan out. Times are on CLOCK_MONOTONIC, the kiosk's clock.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/bench/bench_latency_child.hpp"
#include "core/time.hpp"

typedef struct _XDisplay Display;  // Xlib's, without its macros in every includer

namespace mallet::app::latency {

//! A connection to the X server of the bench's own, closed when its owner goes (also when
//! the owner's constructor throws after opening it).
struct CloseDisplay {
  void operator()(Display* display) const;
};
using DisplayConnection = std::unique_ptr<Display, CloseDisplay>;

//! Xvfb on a free display number (-displayfd), one screen of the given size, no TCP.
class VirtualDisplay {
 public:
  //! Starts it and waits (bounded) until it names its display; throws when it cannot.
  VirtualDisplay(int width, int height);
  const std::string& name() const { return name_; }  //!< ":N"
  Child& server() { return *server_; }

 private:
  std::unique_ptr<Child> server_;
  std::string name_;
};

struct PixelBox {
  int x = 0, y = 0, width = 0, height = 0;
};

//! A connection of the bench's own to that server: it finds the kiosk's window and moves
//! the pointer with XTest. One thread only.
class FakePointer {
 public:
  explicit FakePointer(const std::string& display);

  //! The viewable top-level window of this size (the kiosk's), moved to the screen's
  //! origin if it is not there; its box in screen pixels. Nothing when there is none.
  std::optional<PixelBox> find_window(int width, int height);
  //! The pointer to (x, y) screen pixels; returns when the request was flushed to the server.
  Nanos move_to(int x, int y);
  //! A key pressed and released (an X keysym, e.g. XK_Return), as a keyboard's would arrive.
  void press_key(unsigned long keysym);
  //! The viewable top-level window of width × height resized to to_width × to_height, as a
  //! screen turned to portrait or an operator's drag would; false when there is none.
  bool resize_window(int width, int height, int to_width, int to_height);

 private:
  //! The viewable top-level window of this size; 0 when there is none.
  unsigned long window_of_size(int width, int height);
  DisplayConnection display_;
};

//! One strip of the screen grabbed: the time the request went out, the time the reply
//! came back, and the pixels as 0xRRGGBB, row by row.
struct Grab {
  Nanos sent = 0, received = 0;
  std::vector<std::uint32_t> rgb;
};

//! Grabs strips of the framebuffer on its own connection (Xlib connections are per thread).
class ScreenReader {
 public:
  explicit ScreenReader(const std::string& display);
  //! False when the server refused (the box is off the screen).
  bool grab(const PixelBox& box, Grab& out);

 private:
  DisplayConnection display_;
};

//! Where the mallet head (the white sphere) is in a strip: the lowest row, in screen
//! pixels, of a "white" pixel (every channel ≥ kWhite), or nothing when none is there.
inline constexpr std::uint32_t kWhite = 190;
std::optional<int> lowest_white_row(const Grab& g, const PixelBox& box);

//! The picture of one bar becoming "the mallet at the bar": the first grab whose lowest
//! white row reaches (the row where the head rests on the bar − tolerance) after one that
//! did not. The time is the middle
//! of [the previous grab's request, this grab's reply]: the frame reached the server in
//! between.
struct PictureEvent {
  int strip = 0;     //!< which strip (bar) it was seen in
  Nanos t = 0;       //!< estimate
  Nanos window = 0;  //!< the interval it lies in (its uncertainty)
};

//! A thread that polls strips of the screen (≈1 ms apart) and reports the moments each
//! one starts to show the mallet at its bar. The rows are set by the main thread once
//! they are known (set_rest_row); until then a strip reports nothing.
class PictureWatch {
 public:
  PictureWatch(const std::string& display, std::vector<PixelBox> strips, int tolerance_px);
  ~PictureWatch();
  void set_rest_row(int strip, int row) { rest_rows_[static_cast<std::size_t>(strip)].store(row); }
  //! The events since the last call; throws when the thread failed.
  std::vector<PictureEvent> take();
  double mean_poll_ms() const;
  std::uint64_t polls() const { return polls_.load(); }

 private:
  void run(std::string display);

  std::vector<PixelBox> strips_;
  int tolerance_;
  std::unique_ptr<std::atomic<int>[]> rest_rows_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> polls_{0};
  std::atomic<Nanos> first_poll_{0}, last_poll_{0};
  std::mutex mutex_;
  std::vector<PictureEvent> events_;
  std::string error_;
  std::thread thread_;
};

}  // namespace mallet::app::latency
