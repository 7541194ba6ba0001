#include "audio/engine.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "audio/denormals.hpp"
#include "core/actuator_signal.hpp"
#include "core/sample_clock.hpp"

namespace mallet::audio {

namespace {
constexpr int kMaxBlock = 4096;  // longer requests are rendered in pieces
// The speaker's limiter threshold: below it the note is the synthesis' own samples.
constexpr double kAcousticKnee = 0.9;
}  // namespace

AudioEngine::AudioEngine(const Scene& scene, std::vector<ModalPreset> presets, EngineSettings settings)
    : settings_(settings),
      presets_(std::move(presets)),
      volume_(settings.acoustic_volume),
      gain_(settings.actuator.gain),
      acoustic_limiter_(kAcousticKnee, std::max(settings.sample_rate_hz, 1)),
      actuator_limiter_(settings.actuator.soft_clip_knee, std::max(settings.sample_rate_hz, 1)),
      mixed_limiter_(std::min(kAcousticKnee, settings.actuator.soft_clip_knee), std::max(settings.sample_rate_hz, 1)) {
  const AudioRouting& r = settings_.routing;
  if (settings_.sample_rate_hz < 1000) throw std::invalid_argument("audio: sample rate below 1000 Hz");
  if (r.channels < 1 || r.acoustic < 0 || r.acoustic >= r.channels || r.actuator < 0 || r.actuator >= r.channels)
    throw std::invalid_argument("audio: routing names a channel the device does not have");
  if (settings_.max_voices < 1 || settings_.max_voices > 4096)
    throw std::invalid_argument("audio: max_voices must be in [1, 4096]");
  if (!(settings_.schedule_ahead_ms >= 0 && settings_.schedule_ahead_ms <= 1000))
    throw std::invalid_argument("audio: schedule_ahead_ms must be in [0, 1000]");
  if (presets_.size() != scene.instruments.size())
    throw std::invalid_argument("audio: one acoustic preset per instrument is needed");
  for (const Material& m : scene.materials)
    if (auto problem = actuator_band_problem(m, settings_.sample_rate_hz)) throw std::invalid_argument(*problem);

  targets_.resize(scene.targets.size());
  for (std::size_t i = 0; i < scene.instruments.size(); ++i) {
    for (int id : scene.instruments[i].targets) {
      const Target& t = scene.targets[static_cast<std::size_t>(id)];
      targets_[static_cast<std::size_t>(id)] = {scene.materials[static_cast<std::size_t>(t.material)].actuator,
                                                &presets_[i], t.frequency_hz, static_cast<int>(i), t.note,
                                                scene.instruments[i].speaker};
    }
  }
  for (const Material& m : scene.materials) material_actuator_.push_back(m.actuator);
  if (scene.texture) stripes_.emplace(scene.texture->stripes, settings_.sample_rate_hz);
  pending_motions_.reserve(2 * kRingCapacity);
  voices_.resize(static_cast<std::size_t>(settings_.max_voices));
  pending_.reserve(kMaxPending);
  acoustic_bus_.resize(kMaxBlock);
  actuator_bus_.resize(kMaxBlock);
  ahead_ns_ = static_cast<Nanos>(std::llround(settings_.schedule_ahead_ms * 1e6));
  if (settings_.eq_alignment_samples < 0 || settings_.eq_alignment_samples > 8192)
    throw std::invalid_argument("audio: the actuator inverse's alignment must be 0 to 8192 samples");
  if (!settings_.actuator_eq.empty()) actuator_eq_ = FirFilter(settings_.actuator_eq);
  acoustic_delay_.assign(static_cast<std::size_t>(settings_.eq_alignment_samples), 0.0);
  alignment_ns_ = frames_to_ns(settings_.eq_alignment_samples, settings_.sample_rate_hz);
}

bool AudioEngine::post(const Impact& impact, Producer from) {
  if ((from == Producer::main ? ring_ : input_ring_).push(impact)) return true;
  dropped_.fetch_add(1, std::memory_order_relaxed);
  return false;
}

bool AudioEngine::post_motion(const StripeMotion& motion, Producer from) {
  if (!stripes_) return true;
  if ((from == Producer::main ? motion_ring_ : input_motion_ring_).push(motion)) return true;
  dropped_.fetch_add(1, std::memory_order_relaxed);
  return false;
}

void AudioEngine::schedule_motion(const StripeMotion& motion, std::int64_t block_start) {
  if (pending_motions_.size() == 2 * kRingCapacity) {  // cannot happen: the rings hold no more
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  // Like an impact: on its own sample, never before the block (a late update applies now).
  const SampleAlignment a = align_to_sample(motion.t_ns + ahead_ns_ - origin_ns_, settings_.sample_rate_hz);
  std::int64_t start = std::max(a.index, block_start);
  // Updates apply in order: none before the one queued ahead of it.
  if (!pending_motions_.empty()) start = std::max(start, pending_motions_.back().start);
  pending_motions_.push_back({motion, start});
}

EngineCounters AudioEngine::counters() const {
  EngineCounters c;
  c.impacts = impacts_.load(std::memory_order_relaxed);
  c.dropped = dropped_.load(std::memory_order_relaxed);
  c.late = late_.load(std::memory_order_relaxed);
  c.stolen = stolen_.load(std::memory_order_relaxed);
  c.clipped = clipped_.load(std::memory_order_relaxed);
  c.active_voices = active_.load(std::memory_order_relaxed);
  return c;
}

void AudioEngine::schedule(const Impact& impact, std::int64_t block_start) {
  impacts_.fetch_add(1, std::memory_order_relaxed);
  if (impact.target < 0 || static_cast<std::size_t>(impact.target) >= targets_.size() ||
      !std::isfinite(impact.speed_m_per_s) || pending_.size() == kMaxPending) {
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  Pending p{impact, block_start, 0.0};
  // Heard at the contact plus the route's delay (align = picture, a late decision), plus
  // the constant schedule_ahead.
  const SampleAlignment a =
      align_to_sample(impact.t_ns + impact.delay_ns + ahead_ns_ - origin_ns_, settings_.sample_rate_hz);
  if (a.index >= block_start) {
    p.start = a.index;
    p.delay_s = a.delay_s;
  } else if (ahead_ns_ > 0) {
    late_.fetch_add(1, std::memory_order_relaxed);  // later than the promised constant latency
  }
  pending_.push_back(p);  // within the reserved capacity: no allocation
}

void AudioEngine::start_voice(const Pending& p) {
  Voice* voice = nullptr;
  for (Voice& v : voices_) {
    if (!v.active) {
      voice = &v;
      break;
    }
  }
  if (!voice) {  // steal the quietest, the oldest among equals
    voice = &voices_.front();
    for (Voice& v : voices_) {
      const double e = v.envelope(), best = voice->envelope();
      if (e < best || (e == best && v.serial < voice->serial)) voice = &v;
    }
    stolen_.fetch_add(1, std::memory_order_relaxed);
  }
  const TargetTable& t = targets_[static_cast<std::size_t>(p.impact.target)];
  const int fs = settings_.sample_rate_hz;
  const double v = p.impact.speed_m_per_s;
  // The strike's own material (the wall's can be switched); the target's if none is given.
  const std::size_t m = static_cast<std::size_t>(p.impact.material);
  const VibrationParams& act = p.impact.material >= 0 && m < material_actuator_.size() ? material_actuator_[m]
                                                                                         : t.actuator;
  voice->actuator.start(gain_.load(std::memory_order_relaxed) * act.amplitude * v, act.decay_per_s, act.freq_hz,
                        p.delay_s, fs);
  const bool speaker = settings_.acoustic_enabled && t.speaker;
  if (speaker && !external_) voice->acoustic.strike(*t.preset, t.fundamental_hz, v, p.delay_s, fs);
  else voice->acoustic.stop();
  // An external synth has no sub-sample phase: its note starts on this sample.
  if (speaker && external_) external_->note_on(t.instrument, t.note, v);
  voice->active = true;
  voice->serial = serial_++;
}

void AudioEngine::render(double* acoustic, double* actuator, int frames) {
  if (stripes_) stripes_->add_to(actuator, frames, gain_.load(std::memory_order_relaxed));
  for (Voice& v : voices_) {
    if (!v.active) continue;
    v.actuator.add_to(actuator, frames);
    v.acoustic.add_to(acoustic, frames);
    if (v.envelope() < kSilenceAmplitude) {
      v.active = false;
      v.actuator.stop();
      v.acoustic.stop();
    }
  }
}

void AudioEngine::process(float* out, int frames) {
  ScopedFlushDenormals ftz;
  const AudioRouting& routing = settings_.routing;
  const int channels = routing.channels;
  std::fill(out, out + static_cast<std::ptrdiff_t>(frames) * channels, 0.0f);
  for (int done = 0; done < frames;) {
    const int n = std::min(frames - done, kMaxBlock);
    const std::int64_t block_start = position_;
    while (auto impact = ring_.pop()) schedule(*impact, block_start);
    while (auto impact = input_ring_.pop()) schedule(*impact, block_start);
    while (auto motion = motion_ring_.pop()) schedule_motion(*motion, block_start);
    while (auto motion = input_motion_ring_.pop()) schedule_motion(*motion, block_start);

    std::fill_n(acoustic_bus_.begin(), n, 0.0);
    std::fill_n(actuator_bus_.begin(), n, 0.0);
    // Render in segments that end where the next impact starts, so every voice begins
    // on its own sample.
    for (int frame = 0; frame < n;) {
      const std::int64_t now = block_start + frame;
      for (std::size_t i = 0; i < pending_.size();) {
        if (pending_[i].start <= now) {
          start_voice(pending_[i]);
          pending_[i] = pending_.back();
          pending_.pop_back();
        } else {
          ++i;
        }
      }
      std::size_t applied = 0;
      while (applied < pending_motions_.size() && pending_motions_[applied].start <= now) {
        const StripeMotion& m = pending_motions_[applied++].motion;
        stripes_->motion(m.speed_m_per_s, m.on_texture);
      }
      if (applied) pending_motions_.erase(pending_motions_.begin(), pending_motions_.begin() + static_cast<std::ptrdiff_t>(applied));
      std::int64_t next = block_start + n;
      for (const Pending& p : pending_) next = std::min(next, p.start);
      if (!pending_motions_.empty()) next = std::min(next, pending_motions_.front().start);
      const int end = static_cast<int>(next - block_start);
      render(acoustic_bus_.data() + frame, actuator_bus_.data() + frame, end - frame);
      if (external_) external_->render(acoustic_bus_.data() + frame, end - frame);
      frame = end;
    }

    actuator_eq_.process(actuator_bus_.data(), n);
    if (!acoustic_delay_.empty()) {
      for (int i = 0; i < n; ++i) {
        double& slot = acoustic_delay_[acoustic_delay_pos_];
        std::swap(slot, acoustic_bus_[static_cast<std::size_t>(i)]);
        acoustic_delay_pos_ = acoustic_delay_pos_ + 1 == acoustic_delay_.size() ? 0 : acoustic_delay_pos_ + 1;
      }
    }
    const double volume = volume_.load(std::memory_order_relaxed);
    std::uint64_t clipped = 0;
    float* o = out + static_cast<std::ptrdiff_t>(done) * channels;
    if (routing.acoustic != routing.actuator) {
      // Two signals, two limiters: a loud note never turns the actuator down.
      for (int i = 0; i < n; ++i) {
        const double a = acoustic_limiter_.tick(acoustic_bus_[static_cast<std::size_t>(i)] * volume);
        clipped += acoustic_limiter_.limiting();
        const double t = actuator_limiter_.tick(actuator_bus_[static_cast<std::size_t>(i)]);
        clipped += actuator_limiter_.limiting();
        o[i * channels + routing.acoustic] = static_cast<float>(a);
        o[i * channels + routing.actuator] = static_cast<float>(t);
      }
    } else {
      // One channel carries both: its sum is what must stay under the ceiling.
      for (int i = 0; i < n; ++i) {
        const std::size_t k = static_cast<std::size_t>(i);
        o[i * channels + routing.acoustic] =
            static_cast<float>(mixed_limiter_.tick(acoustic_bus_[k] * volume + actuator_bus_[k]));
        clipped += mixed_limiter_.limiting();
      }
    }
    if (clipped) clipped_.fetch_add(clipped, std::memory_order_relaxed);
    int active = 0;
    for (const Voice& v : voices_) active += v.active;
    active_.store(active, std::memory_order_relaxed);
    position_ += n;
    done += n;
  }
}

}  // namespace mallet::audio
