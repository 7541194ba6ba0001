#include "app/calibration/recording_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <fmt/format.h>

#include "app/common/command_support.hpp"

namespace mallet::app {

namespace {

double rms(std::span<const double> x) {
  double s = 0;
  for (double v : x) s += v * v;
  return x.empty() ? 0.0 : std::sqrt(s / static_cast<double>(x.size()));
}

double db(double v) { return 20.0 * std::log10(std::max(v, 1e-12)); }

}  // namespace

ChannelLevels check_channel(std::span<const double> x, std::size_t lead, std::size_t played, const std::string& what) {
  ChannelLevels levels;
  double peak = 0;
  for (double v : x) peak = std::max(peak, std::abs(v));
  levels.peak_dbfs = db(peak);
  if (peak >= kClipLevel)
    throw MeasurementRefused(
        fmt::format("the {} clips (peak {:.1f} dBFS): lower --level or the input's gain", what, levels.peak_dbfs));
  lead = std::min(lead, x.size());
  const double noise = rms(x.first(lead));
  const double signal = rms(x.subspan(lead, std::min(played, x.size() - lead)));
  levels.snr_db = noise > 0 ? db(signal / noise) : (signal > 0 ? 200.0 : 0.0);
  if (signal <= 0 || levels.snr_db < kMinSnrDb)
    throw MeasurementRefused(fmt::format(
        "the {} records silence ({:.1f} dBFS, {:.1f} dB over the noise before the signal; {} needed): check its "
        "wiring, the input channel and the input's gain, or raise --level",
        what, db(signal), levels.snr_db, kMinSnrDb));
  return levels;
}

std::vector<float> after_silence(std::span<const double> signal, std::size_t lead) {
  std::vector<float> played(lead + signal.size(), 0.0f);
  for (std::size_t i = 0; i < signal.size(); ++i) played[lead + i] = static_cast<float>(signal[i]);
  return played;
}

audio::DuplexRecording record_whole(const audio::DuplexRequest& io, std::span<const float> signal) {
  audio::DuplexRecording rec;
  try {
    for (int attempt = 0; attempt < 3; ++attempt) {
      rec = audio::play_and_record(io, signal);
      if (rec.xruns == 0) break;
    }
  } catch (const audio::NoInput& e) {
    throw MeasurementRefused(e.what());
  }
  return rec;
}

void refuse_measurement(const MeasurementRefused& refused) {
  std::fprintf(stderr, "mallet: %s\n", refused.what());
  std::fflush(stderr);
  finish_with(2);
  std::abort();  // finish_with throws: never reached
}

}  // namespace mallet::app
