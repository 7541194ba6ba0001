#include "core/kiosk_metrics.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace mallet {

namespace {

constexpr Nanos kMs = 1'000'000;

//! Seconds of a nanosecond count, as the nearest double (a bound such as 16.7 ms prints
//! as 0.0167, not 0.016700000000000003).
double seconds_of(Nanos ns) { return static_cast<double>(ns) / 1e9; }

std::string format_count(std::uint64_t n) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, n);
  return std::string(buf, r.ptr);
}

//! HELP text: backslash and line feed escaped (quotes are allowed there).
std::string escape_help(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '\\') out += "\\\\";
    else if (c == '\n') out += "\\n";
    else out += c;
  }
  return out;
}

class Text {
 public:
  void family(std::string_view name, std::string_view type, std::string_view help) {
    out_ += "# HELP ";
    out_ += name;
    out_ += ' ';
    out_ += escape_help(help);
    out_ += "\n# TYPE ";
    out_ += name;
    out_ += ' ';
    out_ += type;
    out_ += '\n';
  }
  //! One sample; `labels` are (name, unescaped value) pairs.
  void sample(std::string_view name, std::initializer_list<std::pair<std::string_view, std::string_view>> labels,
              const std::string& value) {
    out_ += name;
    if (labels.size() > 0) {
      out_ += '{';
      bool first = true;
      for (const auto& [k, v] : labels) {
        if (!first) out_ += ',';
        first = false;
        out_ += k;
        out_ += "=\"";
        out_ += escape_label_value(v);
        out_ += '"';
      }
      out_ += '}';
    }
    out_ += ' ';
    out_ += value;
    out_ += '\n';
  }
  void sample(std::string_view name, const std::string& value) { sample(name, {}, value); }
  //! A family of one unlabelled sample.
  void single(std::string_view name, std::string_view type, std::string_view help, const std::string& value) {
    family(name, type, help);
    sample(name, value);
  }
  void histogram(std::string_view name, std::string_view help, const DurationHistogram& h) {
    family(name, "histogram", help);
    const std::string bucket = std::string(name) + "_bucket";
    const std::vector<Nanos>& bounds = h.upper_bounds_ns();
    for (std::size_t i = 0; i < bounds.size(); ++i)
      sample(bucket, {{"le", format_sample_value(seconds_of(bounds[i]))}}, format_count(h.cumulative(i)));
    sample(bucket, {{"le", "+Inf"}}, format_count(h.count()));
    sample(std::string(name) + "_sum", format_sample_value(seconds_of(h.sum_ns())));
    sample(std::string(name) + "_count", format_count(h.count()));
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

}  // namespace

DurationHistogram::DurationHistogram(std::vector<Nanos> upper_bounds_ns) : bounds_(std::move(upper_bounds_ns)) {
  for (std::size_t i = 0; i < bounds_.size(); ++i)
    if (bounds_[i] <= 0 || (i > 0 && bounds_[i] <= bounds_[i - 1]))
      throw std::invalid_argument("histogram bounds must be > 0 and strictly ascending");
  per_bucket_.assign(bounds_.size() + 1, 0);
}

void DurationHistogram::observe(Nanos duration_ns) {
  const Nanos d = std::max<Nanos>(duration_ns, 0);
  // The first bound ≥ d: `le` is "less than or equal".
  const auto at = std::lower_bound(bounds_.begin(), bounds_.end(), d);
  ++per_bucket_[static_cast<std::size_t>(at - bounds_.begin())];
  ++count_;
  sum_ns_ += d;
}

std::uint64_t DurationHistogram::cumulative(std::size_t i) const {
  std::uint64_t n = 0;
  for (std::size_t k = 0; k <= i && k < per_bucket_.size(); ++k) n += per_bucket_[k];
  return n;
}

std::vector<Nanos> frame_seconds_buckets() {
  return {2 * kMs, 4 * kMs, 8 * kMs, 12 * kMs, 16'700'000, 20 * kMs, 25 * kMs, 33'400'000,
          50 * kMs, 100 * kMs, 250 * kMs, 1000 * kMs};
}

std::vector<Nanos> visitor_session_seconds_buckets() {
  std::vector<Nanos> b;
  for (int s : {5, 10, 20, 30, 60, 120, 180, 300, 600, 1200, 1800, 3600}) b.push_back(s * kNanosPerSecond);
  return b;
}

KioskMetrics::KioskMetrics() : frame_(frame_seconds_buckets()), session_(visitor_session_seconds_buckets()) {}

void KioskMetrics::count_frame(Nanos frame_ns) {
  ++frames_;
  frame_.observe(frame_ns);
}

void KioskMetrics::observe_state(KioskState state, Nanos since, Nanos last_movement) {
  if (state == KioskState::play && state_ == KioskState::attract) {
    ++sessions_;
    in_session_ = true;
    session_start_ = since;
  } else if (state == KioskState::attract && in_session_) {
    in_session_ = false;
    session_.observe(last_movement - session_start_);
  }
  state_ = state;
}

void KioskMetrics::observe_tracking(bool lost, Nanos now) {
  if (lost_ && now > lost_since_) tracking_lost_ns_ += now - lost_since_;
  lost_ = lost;
  lost_since_ = now;
}

std::string escape_label_value(std::string_view value) {
  std::string out;
  out.reserve(value.size());
  for (char c : value) {
    if (c == '\\') out += "\\\\";
    else if (c == '"') out += "\\\"";
    else if (c == '\n') out += "\\n";
    else out += c;
  }
  return out;
}

std::string format_sample_value(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "+Inf" : "-Inf";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, value);
  return std::string(buf, r.ptr);
}

std::string render_prometheus_text(const KioskMetrics& m) {
  Text t;
  const auto number = [](double v) { return format_sample_value(v); };
  t.family("mallet_strikes_total", "counter",
           "Strikes the kiosk delivered (note, actuator and bounce), visitors' and the attract mode's.");
  for (const auto& [labels, n] : m.strikes)
    t.sample("mallet_strikes_total", {{"instrument", labels.first}, {"material", labels.second}}, format_count(n));
  t.single("mallet_visitor_sessions_total", "counter",
           "Visitor sessions: changes from the attract mode to play.",
           format_count(m.visitor_sessions()));
  t.histogram("mallet_visitor_session_seconds",
              "How long visitors played: from the start of play to their last movement before the attract mode.",
              m.session_histogram());
  t.family("mallet_visitor_study_sessions_total", "counter",
           "Visitor micro-study sessions (a visitor accepted its offer), by how they ended.");
  for (const auto& [outcome, n] : m.visitor_study)
    t.sample("mallet_visitor_study_sessions_total", {{"outcome", outcome}}, format_count(n));
  t.single("mallet_frames_total", "counter", "Frames drawn.", format_count(m.frames()));
  t.histogram("mallet_frame_seconds", "Time from one drawn frame to the next.", m.frame_histogram());
  t.single("mallet_audio_xruns_total", "counter",
           "Audio callbacks that came too late (the device played silence).",
           format_count(m.audio_xruns));
  t.single("mallet_audio_output_latency_seconds", "gauge",
           "From a sample leaving the program to it being heard (NaN: no audio device).",
           number(m.audio_output_latency_s));
  t.single("mallet_render_device_lost_total", "counter",
           "Times the Vulkan device was lost and the renderer rebuilt on a new one (the kiosk went on).",
           format_count(m.render_devices_lost));
  t.single("mallet_vulkan_device_memory_bytes", "gauge",
           "Vulkan device memory the renderer holds (its buffers and images; not the swapchain's).",
           number(m.vulkan_device_memory_bytes));
  t.single("mallet_remote_connected", "gauge",
           "1 while the IR tracker runs (the Wii Remote's link, or the camera streaming), else 0.",
           m.remote_connected ? "1" : "0");
  t.single("mallet_remote_battery_ratio", "gauge",
           "The Wii Remote's battery, 1 = fresh cells (NaN: no remote or no report yet).",
           number(m.remote_battery_ratio));
  t.single("mallet_tracking_lost_seconds_total", "counter",
           "Time in play with the remote connected but the stick's LED out of the camera's view.",
           number(seconds_of(m.tracking_lost_ns())));
  t.single("mallet_settings_refused", "gauge",
           "1 while the kiosk runs on its last good settings or the shipped defaults: its own were refused.",
           m.settings_refused ? "1" : "0");
  t.single("mallet_state_folder_writable", "gauge",
           "0 while the kiosk's state folder cannot be written (full, read-only): nothing new is kept.",
           m.state_folder_writable ? "1" : "0");
  t.family("mallet_state", "gauge", "The kiosk's state: 1 for the current one, 0 for the others.");
  for (const auto& [s, name] : kKioskStateNames) t.sample("mallet_state", {{"state", name}}, m.state() == s ? "1" : "0");
  t.single("mallet_uptime_seconds", "gauge",
           "Time since this run of the kiosk started.",
           number(seconds_of(m.uptime_ns)));
  t.single("mallet_restarts_total", "counter",
           "How many times the kiosk started before this run.",
           format_count(m.restarts));
  t.family("mallet_build_info", "gauge", "Always 1; the label says which version runs.");
  t.sample("mallet_build_info", {{"version", m.version}}, "1");
  return t.take();
}

}  // namespace mallet
