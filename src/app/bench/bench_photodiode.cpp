#include "app/bench/bench_photodiode.hpp"

#include <jack/jack.h>

#include <cerrno>
#include <cmath>
#include <map>
#include <stdexcept>

#include "app/bench/bench_latency_jack.hpp"

namespace mallet::app::latency {

namespace {

bool all_white(const Grab& g) {
  for (std::uint32_t p : g.rgb)
    if (((p >> 16) & 0xff) < kWhite || ((p >> 8) & 0xff) < kWhite || (p & 0xff) < kWhite) return false;
  return !g.rgb.empty();
}

}  // namespace

JackPhotodiode::JackPhotodiode(const std::string& server, const std::string& display, PixelBox corner, Nanos panel_lag)
    : panel_lag_(panel_lag) {
  jack_status_t status{};
  client_ = jack_client_open("mallet-photodiode", static_cast<jack_options_t>(JackNoStartServer | JackServerName),
                             &status, server.c_str());
  if (!client_) throw std::runtime_error("bench photodiode: cannot open its JACK client");
  port_ = jack_port_register(client_, "light", JACK_DEFAULT_AUDIO_TYPE, JackPortIsOutput, 0);
  if (!port_) {
    jack_client_close(client_);
    throw std::runtime_error("bench photodiode: cannot register its port");
  }
  rate_ = static_cast<int>(jack_get_sample_rate(client_));
  clock_offset_ns_ = jack_clock_offset_ns();
  jack_set_process_callback(client_, &JackPhotodiode::process, this);
  if (jack_activate(client_) != 0) {
    jack_client_close(client_);
    throw std::runtime_error("bench photodiode: cannot activate its JACK client");
  }
  watcher_ = std::thread([this, display, corner] { watch(display, corner); });
}

JackPhotodiode::~JackPhotodiode() {
  stop_.store(true);
  watcher_.join();
  jack_deactivate(client_);
  jack_client_close(client_);
}

void JackPhotodiode::watch(std::string display, PixelBox corner) {
  try {
    ScreenReader reader(display);
    Grab previous, g;
    bool white = false, first = true;
    while (!stop_.load()) {
      if (!reader.grab(corner, g)) throw std::runtime_error("bench photodiode: the corner is off the screen");
      polls_.fetch_add(1, std::memory_order_relaxed);
      const bool now_white = all_white(g);
      if (!first && now_white != white) {
        // The frame reached the server between the previous grab's request and this one's reply.
        const Nanos t = previous.sent + (g.received - previous.sent) / 2;
        changes_.push(Change{t + panel_lag_, now_white ? 0.5f : 0.0f});
        if (now_white) {
          std::lock_guard lock(mutex_);
          white_.push_back(t);
        }
      }
      white = now_white;
      first = false;
      std::swap(previous, g);
      struct timespec pause {0, 1'000'000};
      nanosleep(&pause, nullptr);
    }
  } catch (const std::exception& e) {
    std::lock_guard lock(mutex_);
    error_ = e.what();
  }
}

std::vector<Nanos> JackPhotodiode::turned_white() {
  std::lock_guard lock(mutex_);
  if (!error_.empty()) throw std::runtime_error(error_);
  return white_;
}

bool JackPhotodiode::wire(int channel) {
  const std::map<std::string, std::vector<std::string>> ins = ports_by_client(client_, JackPortIsInput);
  for (const auto& [client, ports] : ins) {
    if (client.rfind("mallet-", 0) == 0 || static_cast<int>(ports.size()) <= channel) continue;
    const int e = jack_connect(client_, jack_port_name(port_), ports[static_cast<std::size_t>(channel)].c_str());
    if (e == 0 || e == EEXIST) return true;
  }
  return false;
}

int JackPhotodiode::process(std::uint32_t frames, void* self) {
  auto& p = *static_cast<JackPhotodiode*>(self);
  auto* out = static_cast<float*>(jack_port_get_buffer(p.port_, frames));
  // This cycle's first sample reached the "converter" one input latency before its cycle began.
  const Nanos cycle = static_cast<Nanos>(jack_frames_to_time(p.client_, jack_last_frame_time(p.client_))) * 1000 -
                      p.clock_offset_ns_ - p.input_latency_.load(std::memory_order_relaxed);
  for (std::uint32_t i = 0; i < frames; ++i) {
    const Nanos t = cycle + static_cast<Nanos>(std::llround(static_cast<double>(i) * 1e9 / p.rate_));
    for (;;) {
      if (!p.has_next_) {
        const std::optional<Change> c = p.changes_.pop();
        if (!c) break;
        p.next_ = *c;
        p.has_next_ = true;
      }
      if (p.next_.t > t) break;
      if (i == 0 && p.next_.t < cycle) p.late_.fetch_add(1, std::memory_order_relaxed);
      p.level_ = p.next_.level;
      p.has_next_ = false;
    }
    out[i] = p.level_;
  }
  return 0;
}

}  // namespace mallet::app::latency
