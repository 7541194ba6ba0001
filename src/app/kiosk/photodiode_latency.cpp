#include "app/kiosk/photodiode_latency.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/printf.h>

#include "core/calibration_file.hpp"
#include "core/journal.hpp"
#include "core/strike_line.hpp"
#include "core/visitor_language.hpp"

namespace mallet::app {

std::optional<audio::CaptureSpec> photodiode_capture(const TimingConfig& timing) {
  if (timing.photodiode_channel <= 0) return std::nullopt;
  audio::CaptureSpec spec;
  spec.input_device = timing.photodiode_input;
  spec.input_channels = {timing.photodiode_channel - 1};
  // The test's first square a second after it starts, one a second, then the search's 300 ms.
  spec.seconds = LatencyTest::kPulses + 1.5;
  return spec;
}

std::string PhotodiodeLatency::label() const { return fmt::format("photodiode (input channel {})", channel_); }

void PhotodiodeLatency::start(audio::PortAudioOutput* output) {
  if (phase_ == Phase::recording) throw std::logic_error("the photodiode is recording already");
  timing_.reset();
  problem_.clear();
  // capture() reads an atomic the stream's reopening writes: ask once, use that answer.
  audio::StreamCapture* capture = output ? output->capture() : nullptr;
  if (!capture) {
    phase_ = Phase::failed;
    problem_ = label() + ": the sound card's stream does not record it (the log says why it did not open with "
                       "its input); the test shows its squares without timing them";
    journal::warning("{}", problem_.c_str());
    return;
  }
  input_name_ = output->input_device_name();
  capture->arm();
  phase_ = Phase::recording;
  journal::notice("{}: recording \"{}\" while the squares show (PortAudio's input latency {:.3f} ms)", label().c_str(),
                  input_name_.c_str(), output->input_latency_s() * 1e3);
}

void PhotodiodeLatency::poll(Nanos now, const LatencyTest& test, audio::PortAudioOutput* output) {
  if (phase_ != Phase::recording) return;
  // Asked once: a second capture() may answer null (the stream reopened between the two).
  audio::StreamCapture* capture = output ? output->capture() : nullptr;
  if (!capture) {  // the stream closed meanwhile (a reload, a lost device)
    phase_ = Phase::failed;
    problem_ = label() + ": the sound card's stream closed while it recorded: press T again";
    journal::warning("{}", problem_.c_str());
    return;
  }
  if (!test.finished(now) || !capture->complete()) return;
  try {
    timing_ = audio::time_photodiode(capture->recording(), 0, output->input_latency_s(), test.squares(),
                                     label());
  } catch (const std::exception& e) {
    phase_ = Phase::failed;
    problem_ = e.what();
    journal::warning("{}", problem_.c_str());
    return;
  }
  measured_utc_ = utc_timestamp_now();
  for (std::size_t i = 0; i < timing_->pulses.size(); ++i) {
    const audio::PhotodiodePulse& p = timing_->pulses[i];
    if (p.latency_ms)
      journal::info("photodiode: square {} of {}: present t={}, light {:.3f} ms after it", i + 1,
                    timing_->pulses.size(), format_seconds(p.present).c_str(), *p.latency_ms);
    else
      journal::info("photodiode: square {} of {}: {}", i + 1, timing_->pulses.size(),
                    p.present ? "no light seen" : "never shown");
  }
  journal::notice("photodiode: display latency {:.3f} ms (the median; {:.3f} to {:.3f} over {} of {} squares)",
                  timing_->display_latency_ms, timing_->min_ms, timing_->max_ms, timing_->seen, timing_->pulses.size());
  phase_ = Phase::asking;
}

DisplayLatencyMeasurement PhotodiodeLatency::measurement(bool saved) const {
  DisplayLatencyMeasurement m;
  if (!timing_) return m;
  m.measured_utc = measured_utc_;
  m.display_latency_ms = std::round(timing_->display_latency_ms * 1000) / 1000;  // µs: the clock's worth
  m.min_ms = timing_->min_ms;
  m.max_ms = timing_->max_ms;
  m.squares_seen = timing_->seen;
  m.squares = static_cast<int>(timing_->pulses.size());
  m.input_device = input_name_;
  m.photodiode_channel = channel_;
  m.saved = saved;
  return m;
}

std::vector<PageLine> PhotodiodeLatency::page_lines(double setting_ms) const {
  if (phase_ == Phase::failed)
    return {{PageTone::warning, problem_}, {PageTone::warning, tr("Esc: back to the page")}};
  if (phase_ != Phase::asking || !timing_) return {};
  // The figures as the journal and `mallet doctor` write them; the keys in the operator's language.
  return {{PageTone::warning,
           fmt::format("display latency measured: {:.1f} ms ({:.1f} to {:.1f} ms over {} of {} squares); [timing] "
                       "display_latency_ms is {:.1f} ms",
                       timing_->display_latency_ms, timing_->min_ms, timing_->max_ms, timing_->seen,
                       timing_->pulses.size(), setting_ms)},
          {PageTone::warning, tr("Enter saves it as [timing] display_latency_ms    Esc keeps the setting")}};
}

}  // namespace mallet::app
