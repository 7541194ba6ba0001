#pragma once
// The display's latency measured by the kiosk itself: with a photodiode on the screen's
// top-left corner wired to the sound card ([timing] photodiode_channel, or `mallet calibrate
// latency --photodiode`), the kiosk's stream records it (PortAudioOutput::Options::capture),
// and while the operator page's latency test (T) shows its ten squares this times each
// square's light against the present of the frame that showed it
// (audio/photodiode_timing.hpp). The page then shows what was found and asks: Enter saves it
// as [timing] display_latency_ms (a settings drop-in, used from the next reload), Esc keeps
// the setting. Either way the measurement is kept in the state folder (display_latency.toml)
// for `mallet doctor`.
#include <optional>
#include <string>
#include <vector>

#include "app/kiosk/latency_test.hpp"
#include "app/kiosk/operator_page.hpp"
#include "audio/photodiode_timing.hpp"
#include "audio/portaudio_output.hpp"
#include "core/display_latency_record.hpp"

namespace mallet::app {

//! What the kiosk's stream records for a photodiode ([timing] photodiode_channel > 0): that
//! input channel, long enough for the latency test's squares and the light after the last.
std::optional<audio::CaptureSpec> photodiode_capture(const TimingConfig& timing);

class PhotodiodeLatency {
 public:
  enum class Phase {
    idle,       //!< no measurement, or its answer given
    recording,  //!< the test's squares show; the stream records
    asking,     //!< measured: Enter saves, Esc keeps the setting
    failed,     //!< nothing usable: problem() says why (Esc)
  };

  //! `channel` from 1, of the input device `input` ("" = the default input).
  PhotodiodeLatency(int channel, std::string input) : channel_(channel), input_(std::move(input)) {}

  //! The latency test starts now: the stream's recording with it. `output` null or one that
  //! does not record (its input would not open): failed, with why. Not while recording.
  void start(audio::PortAudioOutput* output);
  //! Each frame: once the test's last square is past and the recording complete, times the
  //! squares (one journal line each, then the result) and asks, or fails.
  void poll(Nanos now, const LatencyTest& test, audio::PortAudioOutput* output);

  Phase phase() const { return phase_; }
  const std::string& problem() const { return problem_; }
  //! What was measured, as kept in display_latency.toml (`saved`: the operator's Enter).
  DisplayLatencyMeasurement measurement(bool saved) const;
  //! The answer was given (or the failure seen): back to idle.
  void answered() { phase_ = Phase::idle; }

  //! The page's lines while it asks or has failed (none otherwise), `setting_ms` being
  //! [timing] display_latency_ms in force.
  std::vector<PageLine> page_lines(double setting_ms) const;

 private:
  //! "photodiode (input channel N)", as its lines name it.
  std::string label() const;

  int channel_;
  std::string input_;
  std::string input_name_;  //!< the device the stream opened
  Phase phase_ = Phase::idle;
  std::string problem_;
  std::optional<audio::PhotodiodeTiming> timing_;
  std::string measured_utc_;
};

}  // namespace mallet::app
