#pragma once
// Where a strike goes. This is the one route from a pointer sample to the three cues a
// visitor feels, used by every source (mouse, Wii Remote, ghost player, replay) and every
// product (the window kiosk, the headless run, the study, simulate, the benchmarks):
//
//   PointerSample, stamped where its source read it (t), known to the route at `known`
//     → the hand in world metres (the caller's mapping: calibration, scene)
//     → StrikeLoop: the swept contact solver + contact prediction ([timing] predict_*)
//     → a Strike: the contact (t_ns), when it was decided, when it will be heard and shown
//       ├─ audio: AudioEngine::post on this route's producer ring — both channels start
//       │  on the sample of `heard_ns` ([timing] align: asap | picture)
//       ├─ bounce: the visual vibration restarts (Eq. 1 on the time since t_ns); the head
//       │  a frame draws is view(), safe to read from the render thread
//       └─ log line (strike_line), and on_strike for the caller's own bookkeeping
//
// When the cues are heard and shown:
//   asap:    heard = max(contact, decided): the engine starts it on the next block when
//            that sample is already past, so live it is ≤ one block later than heard_ns;
//            with schedule_ahead (the exact preset) the constant covers the decision, so
//            heard = contact unless the strike is known later than contact + ahead;
//   picture: shown = the present time of the first frame that shows the bounce
//            (PresentClock), heard = shown + display_latency_ms, so touch, sound and
//            picture reach the visitor together. The device's output latency is in the
//            engine's clock origin (the frame heard at a time, not written).
// audio.schedule_ahead_ms delays every heard time by that constant (the exact preset).
//
// Threads: one route per producer thread (the remote's reading thread, the mouse's, the
// main thread's ghost); feed/present/reset on that thread only. view(), strikes() and the
// request_* calls are safe from any thread.
#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>

#include "core/strike_loop.hpp"
#include "audio/engine.hpp"
#include "core/app_config.hpp"
#include "core/one_euro_filter.hpp"
#include "core/present_clock.hpp"
#include "core/scene.hpp"

namespace mallet::app {

//! One strike as the route delivered it.
struct Strike {
  Impact impact;          //!< t_ns: the contact (seen or predicted); delay_ns = heard_ns − t_ns
  Nanos decided_ns = 0;   //!< when the route knew it (the sample's arrival)
  Nanos heard_ns = 0;     //!< when both channels are heard, less audio.schedule_ahead_ms
  Nanos shown_ns = 0;     //!< the present time of the first frame that shows the bounce
  bool stimulus = false;  //!< made by the program (a study's stimulus), not by a hand
};

struct RouteOptions {
  audio::Producer producer = audio::Producer::main;
  bool smooth_view = false;  //!< the 1€ filter on the drawn head (a camera's jitter); never on strikes
  bool log = true;           //!< a log line per strike on stderr
};

class StrikeRoute {
 public:
  //! `engine` may be null (detection only: replay, tests); `picture` may be null (no window:
  //! a frame per refresh of a 60 Hz FIFO display is assumed). All must outlive the route.
  StrikeRoute(const Scene& scene, const AppConfig& config, audio::AudioEngine* engine,
              const PresentClock* picture = nullptr, RouteOptions options = {});

  //! The hand (sphere centre, world metres) at `t` as its source stamped it, known to the
  //! route at `known` (≥ t; the live kiosk passes the arrival, simulate --causal t + the
  //! input delay). Without `known` the route works offline: a strike counts as known at
  //! its contact (simulate without --causal, the compressed headless run).
  std::optional<Strike> feed(Nanos t, Vec2 hand, std::optional<Nanos> known = std::nullopt);
  //! A strike the program makes (a study stimulus at impact.t_ns): all three cues as for
  //! a hand's, decided at `known`.
  Strike present(const Impact& impact, Nanos known);
  //! The next sample starts a new stroke (source changed, tracking lost, Play restarted).
  void reset();

  //! Called on the feeding thread after each strike was posted (counters, rumble, rows).
  std::function<void(const Strike&)> on_strike;

  // --- any thread
  //! The head as the last sample placed it, and the bounce: what a frame draws.
  StrikeLoop::View view() const;
  std::uint64_t strikes() const { return strikes_.load(std::memory_order_relaxed); }
  //! The wall's material from the next sample on (operator page M); applied on the feeding thread.
  void request_wall_material(int material) { wall_material_.store(material, std::memory_order_release); }

  // --- the feeding thread
  StrikeLoop& loop() { return loop_; }
  const StrikeLoop& loop() const { return loop_; }

 private:
  Strike deliver(const Impact& impact, Nanos known, bool stimulus);
  void publish(Nanos t, Vec2 hand);

  const Scene& scene_;
  audio::AudioEngine* engine_;
  const PresentClock* picture_;
  PresentClock fallback_picture_;
  RouteOptions options_;
  TimingConfig timing_;
  Nanos ahead_ns_ = 0;
  StrikeLoop loop_;
  OneEuroFilter filter_;
  mutable std::mutex view_mutex_;
  StrikeLoop::View view_;
  std::atomic<std::uint64_t> strikes_{0};
  std::atomic<int> wall_material_{-1};  //!< a request, -1 = none
};

}  // namespace mallet::app
