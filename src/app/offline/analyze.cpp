#include "app/offline/analyze.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/csv_file.hpp"
#include "audio/wav_file.hpp"
#include "core/file_error.hpp"
#include "core/sample_clock.hpp"

namespace mallet::app {

std::vector<ImpactAnalysis> analyze_simulation(const std::filesystem::path& dir, int actuator_channel) {
  const csv::Table events = csv::read(dir / "events.csv");
  const csv::Table cursor = csv::read(dir / "cursor.csv");
  const audio::WavData wav = audio::read_wav(dir / "audio.wav");
  if (actuator_channel < 0 || actuator_channel >= wav.channels)
    throw FileError((dir / "audio.wav").string(), 0, 0,
                    "has " + std::to_string(wav.channels) + " channels, no channel " +
                        std::to_string(actuator_channel));
  const std::vector<double> act = wav.channel(actuator_channel);

  const std::size_t et = events.column("t"), em = events.column("material"), ev = events.column("velocity");
  const std::size_t ct = cursor.column("t"), co = cursor.column("offset");
  std::vector<Nanos> times;
  for (std::size_t r = 0; r < events.rows.size(); ++r) {
    const auto t = from_seconds(events.number(r, et));
    if (!t) throw FileError(events.file, static_cast<std::uint32_t>(r + 2), 0, "bad time");
    times.push_back(*t);
  }
  std::vector<double> cursor_t, cursor_offset;
  for (std::size_t r = 0; r < cursor.rows.size(); ++r) {
    cursor_t.push_back(cursor.number(r, ct));
    cursor_offset.push_back(cursor.number(r, co));
  }
  double trace_rate = 0;
  if (cursor_t.size() >= 2) trace_rate = static_cast<double>(cursor_t.size() - 1) / (cursor_t.back() - cursor_t.front());

  std::vector<ImpactAnalysis> out;
  for (std::size_t r = 0; r < times.size(); ++r) {
    ImpactAnalysis a;
    a.t_ns = times[r];
    a.material = events.rows[r][em];
    a.velocity = events.number(r, ev);
    const Nanos next = r + 1 < times.size() ? times[r + 1] : std::numeric_limits<Nanos>::max();
    const double t_s = to_seconds(a.t_ns), next_s = to_seconds(next);

    // The visual vibration, as traced.
    const auto first = std::lower_bound(cursor_t.begin(), cursor_t.end(), t_s);
    const auto last = std::lower_bound(first, cursor_t.end(), next_s);
    if (last - first >= 8 && trace_rate > 0) {
      const std::size_t i0 = static_cast<std::size_t>(first - cursor_t.begin());
      a.visual = fit_damped_sine(std::span<const double>(cursor_offset).subspan(i0, static_cast<std::size_t>(last - first)),
                                 trace_rate, cursor_t[i0] - t_s);
    }
    // The actuator signal, from the impact's own sample.
    const SampleAlignment start = align_to_sample(a.t_ns, wav.sample_rate_hz);
    const std::int64_t end = std::min<std::int64_t>(
        static_cast<std::int64_t>(act.size()),
        next == std::numeric_limits<Nanos>::max() ? static_cast<std::int64_t>(act.size())
                                                   : align_to_sample(next, wav.sample_rate_hz).index);
    if (start.index >= 0 && end - start.index >= 8) {
      a.actuator = fit_damped_sine(
          std::span<const double>(act).subspan(static_cast<std::size_t>(start.index),
                                               static_cast<std::size_t>(end - start.index)),
          wav.sample_rate_hz, start.delay_s);
    }
    out.push_back(std::move(a));
  }
  return out;
}

}  // namespace mallet::app
