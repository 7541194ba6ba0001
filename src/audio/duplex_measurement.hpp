#pragma once
// One measurement through the sound card: a prepared signal played on one output channel
// (the others silent) while input channels are recorded, sample-aligned, by a single
// full-duplex PortAudio stream. `mallet calibrate actuator` plays its sweep and its strikes
// this way, `mallet calibrate latency` its clicks.
//
// Recorded frame i is the frame the stream's callback received together with played
// frame i: the chain's delay, sound card included, is in the recording, and it is the same
// for every channel recorded. The callback copies (no allocation, no lock); the caller's
// thread waits for the last frame (bounded) and then closes the stream.
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace mallet::audio {

//! A device that records nothing, or fewer channels than asked for: "this sound card has no
//! input: ...", naming the input devices there are.
class NoInput : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct DuplexRequest {
  std::string output_device;  //!< as [audio] device: empty = the default output
  std::string input_device;   //!< --input: empty = the default input
  int sample_rate_hz = 48000;
  int output_channels = 2;    //!< the stream's (routing.channels)
  int output_channel = 1;     //!< where the signal goes (0-based)
  std::vector<int> input_channels = {0};  //!< what is recorded (0-based)
  double tail_s = 0.5;        //!< recorded after the signal ends
};

struct DuplexRecording {
  int sample_rate_hz = 0;
  std::vector<std::vector<double>> channels;  //!< one per input_channels, signal.size() + tail
  std::string output_name, input_name;
  double output_latency_s = 0;  //!< as PortAudio reports the stream's
  double input_latency_s = 0;
  unsigned long xruns = 0;      //!< callbacks flagged as under- or overflowing
};

//! Throws NoInput, "this sound card has no input: …", for an input
//! device that records nothing (or has fewer channels than asked); std::runtime_error with
//! one line for PortAudio's device errors and a stream that stopped delivering frames.
DuplexRecording play_and_record(const DuplexRequest& request, std::span<const float> signal);

}  // namespace mallet::audio
