#pragma once
// `mallet bench input`'s camera section: what the V4L2 IR tracker's device-free half costs
// and how still it holds a still LED, on frames drawn by led_frame_synth (the generator the
// tests' kept streams come from).
#include <cstdint>

namespace mallet::app::input_bench {

//! Prints the LED finder's cost per 640×480 frame (GREY, YUYV, MJPEG decode and find) in
//! steady tracking, when acquiring and when lost, as median and p99 µs over `frames` calls
//! against the 0.5 ms budget, then the centroid's noise on a still LED for three sensor
//! noise levels. Deterministic tables for a seed except the times.
void print_camera_section(std::uint64_t seed, int frames);

}  // namespace mallet::app::input_bench
