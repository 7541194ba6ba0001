#pragma once
// A camera for tests: it plays frames of a stream, may go away once after some of them, and
// may refuse to open at first; after its frames it waits (a real millisecond) as a camera
// with nothing new does.
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "input/camera/frame_grabber.hpp"
#include "input/camera/frame_stream.hpp"

namespace mallet::input::camera::test {

//! A camera that plays frames, then may go away; opening may fail the first `refuse` times.
class ScriptedGrabber final : public FrameGrabber {
 public:
  struct Script {
    std::vector<test::StreamFrame> frames;
    std::size_t gone_after = SIZE_MAX;  //!< next() fails ("went away") after this many frames
    int refuse_opens = 0;
  };
  explicit ScriptedGrabber(Script script) : script_(std::move(script)) {}

  Result<CameraMode, std::string> open() override {
    std::lock_guard lock(mutex_);
    ++opens_;
    if (opens_ <= script_.refuse_opens) return tl::unexpected(std::string("no camera among /dev/video*"));
    CameraMode m;
    m.device = "/dev/video7";
    m.name = "Scripted Camera";
    m.driver = "test";
    m.width = 160;
    m.height = 120;
    m.rate_hz = 240;
    open_ = true;
    return m;
  }
  Result<bool, GrabError> next(int, CameraFrame& frame) override {
    std::unique_lock lock(mutex_);
    if (delivered_ == script_.gone_after) {
      script_.gone_after = SIZE_MAX;  // gone once; the next open brings it back
      return tl::unexpected(GrabError{"/dev/video7: No such device", true});
    }
    if (delivered_ >= script_.frames.size()) {
      lock.unlock();
      std::this_thread::sleep_for(std::chrono::milliseconds(1));  // a camera with nothing new: a real wait
      return false;
    }
    frame = script_.frames[delivered_++].frame();
    return true;
  }
  void close() override {
    std::lock_guard lock(mutex_);
    open_ = false;
  }
  void wake() override {}
  std::string stamping() const override { return "scripted"; }
  int opens() const {
    std::lock_guard lock(mutex_);
    return opens_;
  }

 private:
  mutable std::mutex mutex_;
  Script script_;
  std::size_t delivered_ = 0;
  int opens_ = 0;
  bool open_ = false;
};

}  // namespace mallet::input::camera::test
