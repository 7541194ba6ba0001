#pragma once
// The figures of `mallet bench soak`: what it samples from the running kiosk once a minute,
// the rows of soak.csv, the growth per hour of each column, and the plot (soak.svg). Pure
// except read_process (which reads /proc).
#include <sys/types.h>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mallet::app::soak {

//! A process as the kernel sees it: resident memory, open descriptors, threads, CPU time.
struct ProcessSample {
  std::uint64_t rss_bytes = 0;  //!< VmRSS
  int fds = 0;                  //!< entries of /proc/PID/fd
  int threads = 0;              //!< Threads
  std::int64_t cpu_ns = 0;      //!< user + system time of all its threads so far (/proc/PID/stat)
};
//! Nothing when the process is gone (or /proc cannot be read).
std::optional<ProcessSample> read_process(pid_t pid);

//! A Prometheus histogram's cumulative buckets: (upper bound in seconds, count ≤ it); the
//! last bound is +Inf.
using Buckets = std::vector<std::pair<double, std::uint64_t>>;

//! What the soak reads from the kiosk's metrics file ([metrics] textfile).
struct KioskFigures {
  Buckets frame_seconds;  //!< mallet_frame_seconds_bucket
  std::uint64_t frames = 0;
  std::uint64_t strikes = 0;  //!< mallet_strikes_total, every label summed
  double vulkan_bytes = std::numeric_limits<double>::quiet_NaN();
};
//! Parses the text exposition the kiosk writes; nothing when a family the soak needs is missing.
std::optional<KioskFigures> parse_kiosk_figures(std::string_view text);

//! The q-quantile of the observations made between two readings of one histogram, as
//! Prometheus' histogram_quantile computes it (linear within the bucket it falls in; the
//! highest finite bound when it falls in +Inf). NaN when nothing was observed.
double histogram_quantile(double q, const Buckets& now, const Buckets& before);

//! One row of soak.csv: one sample, usually a minute after the one before.
struct Minute {
  double hours = 0;             //!< since the kiosk was up
  double rss_mib = 0;           //!< of the kiosk process
  int fds = 0, threads = 0;
  double vulkan_mib = 0;        //!< mallet_vulkan_device_memory_bytes
  std::uint64_t strokes = 0;    //!< the scripted visitor's strokes in this minute
  std::uint64_t strikes = 0;    //!< strikes the kiosk logged (visitor's and attract mode's)
  std::uint64_t actuator = 0;   //!< of those, the ones whose onset was found on the actuator channel
  std::uint64_t note = 0;       //!< … and on the note channel
  std::uint64_t lost = 0;       //!< strikes with a channel where no onset was found
  std::uint64_t xruns = 0;      //!< JACK cycles that came late (the bench's server, this machine's load)
  std::uint64_t frames = 0;     //!< drawn in this minute
  double frame_p99_ms = 0;      //!< this minute's frames (histogram_quantile)
  std::string state;            //!< "play" or "away": what the scripted visitor did mid-row
};

//! The header line of soak.csv (no line feed) and one row.
std::string csv_header();
std::string csv_row(const Minute& m);

//! The least-squares slope of y over x (per unit of x); 0 with fewer than two points.
double slope(const std::vector<double>& x, const std::vector<double>& y);

//! The growth per hour of each figure that must not grow: (column, slope, unit).
struct Growth {
  std::string column, unit;
  double per_hour = 0;
};
std::vector<Growth> growth_per_hour(const std::vector<Minute>& rows);

//! soak.svg: one panel per figure over the hours, with its growth per hour in the title.
std::string svg_plot(const std::vector<Minute>& rows);

}  // namespace mallet::app::soak
