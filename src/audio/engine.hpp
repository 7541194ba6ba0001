#pragma once
// The real-time audio engine: impacts in, two signals out — the acoustic note for the
// speaker and Eq. 1 for the stick's voice coil — routed to the device's channels.
//
// THE CALLBACK CONTRACT. process() runs on the audio thread and never locks,
// allocates, logs, throws or waits. Everything it touches is preallocated by the
// constructor: the event rings, the voice pool, the per-target tables. Impacts arrive
// only through post() over lock-free SPSC rings, one per producer thread (the kiosk's
// main thread plays the mouse and the attract mode's ghost; the Wii Remote's reading
// thread posts the visitor's strikes itself, so they never wait for a frame). Counters are
// relaxed atomics that other threads may read.
//
// Sample-accurate scheduling: an impact at time t (ns, monotonic clock) starts on
// the first sample at or after t + delay_ns + schedule_ahead − origin (delay_ns: the strike
// route's, see app/strike_route.hpp), with its exact sub-sample
// phase, even inside a block. With schedule_ahead = 0 an impact that is already past
// starts at the beginning of the next block (as soon as possible: jitter up to one
// block); with schedule_ahead > 0 every impact is delayed by exactly that constant
// latency (no jitter), unless it arrives later than that (counted as late).
// Both channels of one impact start on the same sample.
//
// Voice pool: a fixed number of voices; each impact takes one (actuator + acoustic).
// A voice is retired when both envelopes are below −100 dB of full scale. When all
// voices are busy the quietest voice is stolen (ties: the oldest).
//
// Output limit: after the volume and the gain, each signal passes its own zero-latency
// peak limiter (audio/peak_limiter.hpp; threshold 0.9 for the note, soft_clip_knee for the
// actuator, ceiling PeakLimiter::kCeiling), so no setting drives a channel to full scale and
// nothing is delayed. When both signals share one channel, their sum is limited instead.
//
// Actuator inverse: with EngineSettings::actuator_eq (the taps of actuator_eq.toml, in force
// when [actuator] equalize allows), the actuator signal passes that FIR filter
// (audio/fir_filter.hpp) before its limiter. Where the filter's latency is positive the
// speaker's note is delayed by the same whole samples (eq_alignment_samples), so both
// channels of a strike are still heard on one sample, and the engine's origin (frame 0's
// time) moves by as much: heard times stay true.
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "audio/damped_oscillator.hpp"
#include "audio/fir_filter.hpp"
#include "audio/modal_bar.hpp"
#include "audio/peak_limiter.hpp"
#include "audio/spsc_ring.hpp"
#include "core/app_config.hpp"
#include "core/impact.hpp"
#include "core/scene.hpp"
#include "core/stripe_signal.hpp"

namespace mallet::audio {

//! An acoustic source outside the engine's own modal voices (the FluidSynth route).
//! Both methods are called only from the audio thread, inside process(), under the
//! callback contract above.
class ExternalAcoustic {
 public:
  virtual ~ExternalAcoustic() = default;
  //! A strike on `instrument` (index in Scene::instruments) starts now, at the next
  //! rendered frame.
  virtual void note_on(int instrument, int note, double speed_m_per_s) = 0;
  //! Adds `frames` frames of the speaker's signal to `out`.
  virtual void render(double* out, int frames) = 0;
};

struct EngineSettings {
  int sample_rate_hz = 48000;
  AudioRouting routing;
  ActuatorConfig actuator;
  double schedule_ahead_ms = 0.0;
  int max_voices = 64;
  double acoustic_volume = 1.0;     //!< gain of the speaker channel (operator volume)
  bool acoustic_enabled = true;     //!< false: the speaker channel is silent
  std::vector<double> actuator_eq;  //!< the actuator inverse's taps; empty = none
  int eq_alignment_samples = 0;     //!< the speaker's delay that keeps it with the inverse (0..8192)
};

struct EngineCounters {
  std::uint64_t impacts = 0;   //!< events taken from the ring
  std::uint64_t dropped = 0;   //!< ring full at post()
  std::uint64_t late = 0;      //!< started after their scheduled sample
  std::uint64_t stolen = 0;    //!< voices taken from a sounding impact
  std::uint64_t clipped = 0;   //!< samples (per signal) the output limiter turned down
  int active_voices = 0;
};

//! Which thread posts: each has its own single-producer ring.
enum class Producer { main, input };

class AudioEngine {
 public:
  static constexpr std::size_t kRingCapacity = 1024;
  static constexpr std::size_t kMaxPending = 2 * kRingCapacity;  //!< all the rings can deliver at once

  //! `presets[i]` is the acoustic preset of scene.instruments[i]. Throws (before any
  //! audio runs) if they do not match or a setting is out of range.
  AudioEngine(const Scene& scene, std::vector<ModalPreset> presets, EngineSettings settings);

  //! Producer side (one thread per Producer): queue an impact. False if the ring is full.
  bool post(const Impact& impact, Producer from = Producer::main);
  //! Producer side (the same threads): the texture scene's cursor motion for the
  //! vibrotactile stripes, scheduled on its own sample like an impact. Ignored (true) in
  //! scenes without a texture; false if the ring is full.
  bool post_motion(const StripeMotion& motion, Producer from = Producer::main);

  //! The monotonic-clock time of frame 0. Set before the stream starts.
  //! `origin_ns` is when the device plays frame 0; the engine's own origin is later by the
  //! inverse's alignment (what it renders at frame i is heard at frame i + alignment).
  void set_origin(Nanos origin_ns) { origin_ns_ = origin_ns + alignment_ns_; }
  Nanos origin() const { return origin_ns_; }

  //! Replaces the modal voices as the speaker's source (nullptr: back to modal). Call
  //! before the stream starts; the engine does not own it.
  void set_external_acoustic(ExternalAcoustic* source) { external_ = source; }

  //! Audio callback: writes `frames` interleaved frames of settings.routing.channels.
  void process(float* out, int frames);

  std::int64_t position() const { return position_; }  //!< frames rendered so far
  EngineCounters counters() const;
  const EngineSettings& settings() const { return settings_; }

  //! Operator knobs, safe to call from any thread.
  void set_acoustic_volume(double v) { volume_.store(v, std::memory_order_relaxed); }
  void set_actuator_gain(double g) { gain_.store(g, std::memory_order_relaxed); }

 private:
  struct Voice {
    bool active = false;
    std::uint64_t serial = 0;  //!< start order, for "oldest"
    DampedOscillator actuator;
    ModalBarVoice acoustic;
    double envelope() const { return actuator.envelope() + acoustic.envelope(); }
  };
  struct Pending {
    Impact impact;
    std::int64_t start = 0;  //!< sample index
    double delay_s = 0;      //!< sub-sample offset
  };
  struct PendingMotion {
    StripeMotion motion;
    std::int64_t start = 0;
  };
  struct TargetTable {
    VibrationParams actuator;
    const ModalPreset* preset = nullptr;
    double fundamental_hz = 0;
    int instrument = 0;
    int note = 0;
    bool speaker = true;  //!< Instrument::speaker
  };

  void schedule(const Impact& impact, std::int64_t block_start);
  void schedule_motion(const StripeMotion& motion, std::int64_t block_start);
  void start_voice(const Pending& p);
  void render(double* acoustic, double* actuator, int frames);

  EngineSettings settings_;
  std::vector<ModalPreset> presets_;
  std::vector<TargetTable> targets_;
  std::vector<VibrationParams> material_actuator_;  //!< per Scene::materials, for Impact::material
  SpscRing<Impact, kRingCapacity> ring_;        //!< Producer::main
  SpscRing<Impact, kRingCapacity> input_ring_;  //!< Producer::input
  SpscRing<StripeMotion, kRingCapacity> motion_ring_;        //!< Producer::main
  SpscRing<StripeMotion, kRingCapacity> input_motion_ring_;  //!< Producer::input
  std::vector<PendingMotion> pending_motions_;  //!< in arrival order; capacity 2 × kRingCapacity
  std::optional<StripeSignal> stripes_;          //!< texture scenes only
  std::vector<Voice> voices_;
  std::vector<Pending> pending_;  //!< capacity kMaxPending, never grows in process()
  std::vector<double> acoustic_bus_, actuator_bus_;
  ExternalAcoustic* external_ = nullptr;
  Nanos origin_ns_ = 0;
  Nanos ahead_ns_ = 0;
  std::int64_t position_ = 0;
  std::uint64_t serial_ = 0;
  std::atomic<double> volume_;
  std::atomic<double> gain_;
  PeakLimiter acoustic_limiter_, actuator_limiter_;  //!< when the two signals have their own channels
  PeakLimiter mixed_limiter_;                         //!< when they share one
  FirFilter actuator_eq_;                //!< the actuator inverse (inactive without taps)
  std::vector<double> acoustic_delay_;   //!< the speaker's alignment ring (eq_alignment_samples)
  std::size_t acoustic_delay_pos_ = 0;
  Nanos alignment_ns_ = 0;
  std::atomic<std::uint64_t> impacts_{0}, dropped_{0}, late_{0}, stolen_{0}, clipped_{0};
  std::atomic<int> active_{0};
  static_assert(std::atomic<double>::is_always_lock_free);
  static_assert(std::atomic<std::uint64_t>::is_always_lock_free);
};

}  // namespace mallet::audio
