#include "app/bench/bench_latency_jack.hpp"

#include <jack/jack.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <thread>

namespace mallet::app::latency {

namespace {

void quiet(const char*) {}

//! libjack prints every failed connection attempt; the bench says what matters itself.
void silence_libjack() {
  jack_set_error_function(&quiet);
  jack_set_info_function(&quiet);
}

jack_client_t* open_client(const char* client_name, const std::string& server) {
  jack_status_t status{};
  return jack_client_open(client_name, static_cast<jack_options_t>(JackNoStartServer | JackServerName), &status,
                          server.c_str());
}

}  // namespace

JackServer::JackServer(const std::string& name, int rate, int period, int capture) : name_(name) {
  silence_libjack();
  ChildOptions o;
  o.argv = {"jackd", "--no-realtime", "-n", name, "-d", "dummy"};
  o.argv.insert(o.argv.end(), {"-r", std::to_string(rate), "-p", std::to_string(period)});
  if (capture > 0) o.argv.insert(o.argv.end(), {"-C", std::to_string(capture)});
  // No D-Bus device reservation (there is no card to reserve), nothing preloaded (the
  // sanitizer tests preload the Vulkan driver into the bench).
  o.env = {{"JACK_NO_AUDIO_RESERVATION", "1"}, {"LD_PRELOAD", ""}};
  server_ = std::make_unique<Child>(std::move(o));
  const Nanos deadline = monotonic_now() + 10 * kNanosPerSecond;
  while (monotonic_now() < deadline && server_->running()) {
    if (jack_client_t* c = open_client("mallet-bench-probe", name)) {
      jack_client_close(c);
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  throw std::runtime_error("jackd did not accept clients within 10 s (" + server_->ended_how() + "):\n" +
                           server_->tail(8));
}

Nanos AudioTrack::time_of(std::size_t i) const {
  auto after =
      std::upper_bound(blocks.begin(), blocks.end(), i, [](std::size_t v, const Block& b) { return v < b.index; });
  if (after == blocks.begin())
    return blocks.empty() ? 0
                          : blocks.front().t - static_cast<Nanos>(blocks.front().index - i) * kNanosPerSecond / rate;
  const Block& b = *(after - 1);
  return b.t + static_cast<Nanos>(i - b.index) * kNanosPerSecond / rate;
}

std::vector<Gap> AudioTrack::irregular(int period) const {
  std::vector<Gap> gaps;
  const Nanos nominal = static_cast<Nanos>(period) * kNanosPerSecond / rate;
  for (std::size_t k = 1; k < blocks.size(); ++k) {
    const Nanos dt = blocks[k].t - blocks[k - 1].t;
    if (std::llabs(dt - nominal) <= 200'000 &&
        blocks[k].index - blocks[k - 1].index == static_cast<std::size_t>(period))
      continue;
    const std::size_t begin = blocks[k - 1].index, end = blocks[k].index + 2 * static_cast<std::size_t>(period);
    if (!gaps.empty() && begin <= gaps.back().end)
      gaps.back().end = std::max(gaps.back().end, end);
    else
      gaps.push_back({begin, end});
  }
  return gaps;
}

std::size_t AudioTrack::index_at(Nanos t) const {
  auto after = std::upper_bound(blocks.begin(), blocks.end(), t, [](Nanos v, const Block& b) { return v < b.t; });
  if (after == blocks.begin()) return 0;
  const Block& b = *(after - 1);
  return b.index + static_cast<std::size_t>((t - b.t) * rate / kNanosPerSecond);
}

JackRecorder::JackRecorder(const std::string& server, int channels) {
  silence_libjack();
  client_ = open_client("mallet-bench-recorder", server);
  if (!client_) throw std::runtime_error("cannot open a JACK client on the bench's server " + server);
  rate_ = static_cast<int>(jack_get_sample_rate(client_));
  period_ = static_cast<int>(jack_get_buffer_size(client_));
  for (int c = 0; c < channels; ++c) {
    const std::string port = "in_" + std::to_string(c);
    jack_port_t* p = jack_port_register(client_, port.c_str(), JACK_DEFAULT_AUDIO_TYPE, JackPortIsInput, 0);
    if (!p) {
      jack_client_close(client_);
      throw std::runtime_error("cannot register the JACK port " + port);
    }
    ports_.push_back(p);
    samples_.push_back(std::make_unique<float[]>(kFrames));
  }
  stamps_ = std::make_unique<Stamp[]>(kCycles);
  jack_set_process_callback(client_, &JackRecorder::process, this);
  jack_set_xrun_callback(client_, &JackRecorder::xrun, this);
  if (jack_activate(client_) != 0) {
    jack_client_close(client_);
    throw std::runtime_error("cannot activate the JACK recorder");
  }
  // What a device driven by this server adds after the cycle: the playback ports' latency.
  if (jack_port_t* playback = jack_port_by_name(client_, "system:playback_1")) {
    jack_latency_range_t range{};
    jack_port_get_latency_range(playback, JackPlaybackLatency, &range);
    playback_latency_ns_ = static_cast<Nanos>(range.max) * kNanosPerSecond / rate_;
  }
  measure_clock();
}

JackRecorder::~JackRecorder() {
  jack_deactivate(client_);
  jack_client_close(client_);
}

Nanos jack_clock_offset_ns() {
  Nanos best_span = kNanosPerSecond, offset = 0;
  for (int i = 0; i < 50; ++i) {
    const Nanos a = monotonic_now();
    const jack_time_t j = jack_get_time();
    const Nanos b = monotonic_now();
    if (b - a < best_span) {
      best_span = b - a;
      offset = static_cast<Nanos>(j) * 1000 - (a + b) / 2;
    }
  }
  return offset;
}

void JackRecorder::measure_clock() { clock_offset_ns_ = jack_clock_offset_ns(); }

int JackRecorder::process(std::uint32_t frames, void* self) {
  auto* r = static_cast<JackRecorder*>(self);
  r->cycles_.fetch_add(1, std::memory_order_relaxed);
  if (!r->recording_.load(std::memory_order_acquire)) return 0;
  const std::uint64_t w = r->frames_written_.load(std::memory_order_relaxed);
  const std::uint64_t sw = r->stamps_written_.load(std::memory_order_relaxed);
  if (w - r->frames_read_.load(std::memory_order_acquire) + frames > kFrames ||
      sw - r->stamps_read_.load(std::memory_order_acquire) >= kCycles) {
    r->dropped_.fetch_add(1, std::memory_order_relaxed);
    return 0;
  }
  const std::uint64_t at = w % kFrames;
  const std::uint64_t first_part = std::min<std::uint64_t>(frames, kFrames - at);
  for (std::size_t c = 0; c < r->ports_.size(); ++c) {
    const auto* x = static_cast<const float*>(jack_port_get_buffer(r->ports_[c], frames));
    float* ring = r->samples_[c].get();
    std::copy(x, x + first_part, ring + at);
    std::copy(x + first_part, x + frames, ring);
  }
  // This cycle's first frame, on the JACK clock (µs): when its buffers start.
  const Nanos cycle = static_cast<Nanos>(jack_frames_to_time(r->client_, jack_last_frame_time(r->client_))) * 1000;
  r->stamps_[sw % kCycles] = Stamp{w, cycle};
  r->frames_written_.store(w + frames, std::memory_order_release);
  r->stamps_written_.store(sw + 1, std::memory_order_release);
  return 0;
}

int JackRecorder::xrun(void* self) {
  static_cast<JackRecorder*>(self)->xruns_.fetch_add(1, std::memory_order_relaxed);
  return 0;
}

std::map<std::string, std::vector<std::string>> ports_by_client(jack_client_t* self, unsigned long flags) {
  const std::string own = std::string(jack_get_client_name(self)) + ":";
  std::map<std::string, std::vector<std::string>> by_client;
  if (const char** names = jack_get_ports(self, nullptr, JACK_DEFAULT_AUDIO_TYPE, flags)) {
    for (const char** n = names; *n; ++n) {
      const std::string name = *n;
      if (name.rfind("system:", 0) == 0 || name.rfind(own, 0) == 0) continue;
      by_client[name.substr(0, name.find(':'))].push_back(name);
    }
    jack_free(names);
  }
  for (auto& [client, names] : by_client)
    std::sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) {
      return a.size() != b.size() ? a.size() < b.size() : a < b;
    });
  return by_client;
}

std::vector<std::string> JackRecorder::connect_source(std::chrono::milliseconds timeout) {
  const Nanos deadline = monotonic_now() + std::chrono::duration_cast<std::chrono::nanoseconds>(timeout).count();
  do {
    for (auto& [client, names] : ports_by_client(client_, JackPortIsOutput)) {
      if (names.size() < ports_.size()) continue;
      std::vector<std::string> connected;
      for (std::size_t c = 0; c < ports_.size(); ++c) {
        const int e = jack_connect(client_, names[c].c_str(), jack_port_name(ports_[c]));
        if (e != 0 && e != EEXIST) break;
        connected.push_back(names[c]);
      }
      if (connected.size() == ports_.size()) {
        measure_clock();
        return connected;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  } while (monotonic_now() < deadline);
  return {};
}

void JackRecorder::start_recording(AudioTrack& track) {
  // A callback that saw the flag still set finishes its cycle first.
  if (recording_.exchange(false, std::memory_order_acq_rel)) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  // Whatever is still in the rings is dropped: the consumer may advance its own counts.
  frames_read_.store(frames_written_.load(std::memory_order_acquire), std::memory_order_release);
  stamps_read_.store(stamps_written_.load(std::memory_order_acquire), std::memory_order_release);
  track_origin_ = frames_read_.load(std::memory_order_relaxed);
  track = AudioTrack{};
  track.rate = rate_;
  track.channels.resize(ports_.size());
  recording_.store(true, std::memory_order_release);
}

void JackRecorder::forget_before(AudioTrack& track, std::size_t index) {
  for (std::vector<float>& c : track.channels) {
    const std::size_t n = std::min(index, c.size());
    c.erase(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(n));
  }
  // The last cycle that starts at or before `index` stays (it times the first kept sample).
  auto after = std::upper_bound(track.blocks.begin(), track.blocks.end(), index,
                                [](std::size_t v, const AudioTrack::Block& b) { return v < b.index; });
  if (after != track.blocks.begin()) --after;
  const std::size_t first = after == track.blocks.end() ? index : after->index;
  const Nanos first_t = after == track.blocks.end() ? 0 : after->t;
  track.blocks.erase(track.blocks.begin(), after);
  if (!track.blocks.empty() && first < index) {  // re-anchor it at the first kept sample
    track.blocks.front().index = index;
    track.blocks.front().t = first_t + static_cast<Nanos>(index - first) * kNanosPerSecond / track.rate;
  }
  for (AudioTrack::Block& b : track.blocks) b.index -= index;
  track_origin_ += index;
}

bool JackRecorder::follow_source() {
  const bool wired = std::all_of(ports_.begin(), ports_.end(), [](jack_port_t* p) { return jack_port_connected(p) > 0; });
  if (wired || connect_source(std::chrono::milliseconds(0)).empty()) return false;
  ++reopens_followed_;
  return true;
}

void JackRecorder::drain(AudioTrack& track) {
  follow_source();
  const std::uint64_t w = frames_written_.load(std::memory_order_acquire);
  const std::uint64_t r = frames_read_.load(std::memory_order_relaxed);
  for (std::size_t c = 0; c < ports_.size(); ++c)
    for (std::uint64_t f = r; f < w; ++f) track.channels[c].push_back(samples_[c][f % kFrames]);
  frames_read_.store(w, std::memory_order_release);
  const std::uint64_t sw = stamps_written_.load(std::memory_order_acquire);
  for (std::uint64_t s = stamps_read_.load(std::memory_order_relaxed); s < sw; ++s) {
    const Stamp& st = stamps_[s % kCycles];
    track.blocks.push_back(
        {static_cast<std::size_t>(st.frame - track_origin_), st.jack_ns - clock_offset_ns_ + playback_latency_ns_});
  }
  stamps_read_.store(sw, std::memory_order_release);
}

}  // namespace mallet::app::latency
