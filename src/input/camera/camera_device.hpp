#pragma once
// A V4L2 camera as the kiosk's IR tracker: the reading thread over a FrameGrabber (the
// V4L2 capture, or a stream in tests) and a CameraTracker, handing each frame's LedSample
// to the same sink as the Wii Remote's device (remote_pointer.hpp takes both).
//
// Threads. start() reads on its own thread: grabber.next() with a bounded wait, so stop()
// returns promptly (it also wakes the wait). A camera that cannot be opened or goes away
// (unplugged) is said in status(), and the thread opens it again every reopen_interval_ns
// until stop(), as the remote and the mouse do. Nothing throws across the thread.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "core/app_config.hpp"
#include "input/camera/camera_tracker.hpp"
#include "input/camera/frame_grabber.hpp"
#include "input/clock.hpp"
#include "input/evdev/rate_meter.hpp"

namespace mallet::input::camera {

struct CameraDeviceConfig {
  LedFinderConfig finder;
  double lost_after_ms = 150.0;               //!< [tracking] lost_after_ms
  Nanos reopen_interval_ns = kNanosPerSecond;  //!< after a failed open or the camera went away
  int wait_ms = 100;                           //!< one wait's bound (how soon stop() is seen)
};

//! The kiosk's camera device settings from its settings ([tracking] lost_after_ms; the
//! finder's and the reopening's defaults), as wiimote::device_config is the remote's.
CameraDeviceConfig camera_device_config(const AppConfig& config);

//! The reading thread's latest state, for the operator page, the log and `camera monitor`.
struct CameraStatus {
  bool connected = false;
  CameraMode mode;              //!< the last open's
  std::string problem;          //!< why not connected (or the last unreadable frame)
  double rate_hz = 0;           //!< frames stamped in the last second
  bool led_seen = false;        //!< tracking the LED now
  std::optional<IrPoint> led;   //!< the last LED found, camera px
  int led_area_px = 0;
  CameraTrackerCounters counters;
  std::string last_bad_frame;   //!< why the last unreadable frame was (counters.bad_frames)
  std::uint64_t reconnects = 0;
  std::uint64_t losses = 0;     //!< times the open camera failed or went away (not stop())
  std::string last_loss;        //!< why it last did, kept after the reopening
};

class CameraDevice {
 public:
  using SampleSink = wiimote::WiimoteDevice::SampleSink;

  //! `clock` must outlive the device.
  CameraDevice(std::unique_ptr<FrameGrabber> grabber, Clock& clock, CameraDeviceConfig config = {});
  ~CameraDevice();
  CameraDevice(const CameraDevice&) = delete;
  CameraDevice& operator=(const CameraDevice&) = delete;

  //! Before start(): where each frame's sample goes (on the reading thread).
  void set_sample_sink(SampleSink sink) { sink_ = std::move(sink); }
  //! No-op while running.
  void start();
  //! Returns once the thread has ended; safe to call twice or unstarted.
  void stop();
  //! Any thread.
  CameraStatus status() const;
  //! "camera /dev/video0 (USB Camera, uvcvideo) 640x480 grey at 240 Hz", or "camera: " and
  //! why there is none. Any thread.
  std::string describe() const;

 private:
  void run();
  bool connect();
  void publish(bool connected, const std::string& problem);

  std::unique_ptr<FrameGrabber> grabber_;
  Clock& clock_;
  const CameraDeviceConfig config_;
  SampleSink sink_;
  // Reading-thread state.
  CameraTracker tracker_;
  evdev::RateMeter rate_{4096};
  std::uint64_t reconnects_ = 0;
  std::uint64_t losses_ = 0;
  std::string last_loss_;
  bool ever_connected_ = false;
  // Shared.
  mutable std::mutex mutex_;
  CameraStatus status_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

//! "640x480 grey at 240 Hz" (the agreed rate; "?" when the driver would not say).
std::string mode_text(const CameraMode& mode);

}  // namespace mallet::input::camera
