#pragma once
// A frame's time is the middle of its exposure: the LED's centroid in a frame is where the
// LED was on average while the sensor integrated, i.e. at mid-exposure. V4L2 drivers stamp
// a buffer with the kernel's monotonic clock (V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC, the
// program's own clock) either at the start of the exposure (SOE; uvcvideo) or at the end
// of the frame (EOF; the default, vivid's): the stamp is moved by half the exposure. With a
// 500 µs exposure that is 0.25 ms; with a webcam's automatic 33 ms it is 16.7 ms, a whole
// strike's latency budget.
#include "core/time.hpp"

namespace mallet::input::camera {

enum class StampSource {
  start_of_exposure,  //!< V4L2_BUF_FLAG_TSTAMP_SRC_SOE
  end_of_exposure,    //!< V4L2_BUF_FLAG_TSTAMP_SRC_EOF
  read_time,          //!< no monotonic stamp from the driver: the time the frame was read
};

//! The frame's time at mid-exposure from the driver's stamp. A read time is taken as the
//! end of the exposure (the frame cannot have been read before it ended).
constexpr Nanos mid_exposure_ns(Nanos stamp_ns, StampSource source, Nanos exposure_ns) {
  if (exposure_ns < 0) exposure_ns = 0;
  return source == StampSource::start_of_exposure ? stamp_ns + exposure_ns / 2 : stamp_ns - exposure_ns / 2;
}

//! What the log and `camera monitor` say about it.
constexpr const char* describe(StampSource source) {
  switch (source) {
    case StampSource::start_of_exposure: return "the kernel's stamp at the exposure's start, moved to its middle";
    case StampSource::end_of_exposure: return "the kernel's stamp at the frame's end, moved to the exposure's middle";
    case StampSource::read_time: return "the driver gives no monotonic stamp: the time each frame was read";
  }
  return "?";
}

}  // namespace mallet::input::camera
