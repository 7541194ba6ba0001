#pragma once
// The operator page's latency test (T): kPulses times, one a second, a white square in the
// top-left corner, a strike's note on the speaker and its pulse on the actuator, all
// scheduled for the same instant. A photodiode and a microphone (or a 240 fps video) show
// the offsets the operator then enters as [timing] display_latency_ms and
// audio_output_latency_ms. With a photodiode on the corner ([timing] photodiode_channel) the
// kiosk times the squares' light itself (photodiode_latency.hpp): each square's present is
// kept (squares()).
#include <string>
#include <vector>

#include "audio/engine.hpp"
#include "audio/photodiode_timing.hpp"
#include "core/scene.hpp"
#include "core/time.hpp"

namespace mallet::app {

class LatencyTest {
 public:
  static constexpr int kPulses = 10;

  //! Posts the pulses (the scene's first bar, a firm strike) from a second after `now`, each
  //! heard at its instant on the engine's clock; says so in the journal.
  void start(Nanos now, const Scene& scene, audio::AudioEngine& engine);
  //! Whether the frame presented at `present` shows the square: at or after an instant,
  //! for 100 ms.
  bool square_shown(Nanos present);
  //! Each square of the last test: its instant and the present of the first frame that
  //! showed it (0: none yet).
  const std::vector<audio::PhotodiodeSquare>& squares() const { return squares_; }
  //! Whether every square's time is past, its last shown and gone, at `now`.
  bool finished(Nanos now) const { return !all_.empty() && now >= all_.back() + kShown; }
  //! What the operator page says of it at `now`: "" before a test or once its "done" has
  //! shown for kDoneShownFor; else "latency test: pulse 3 of 10", then "latency test: done".
  std::string status(Nanos now) const;
  //! From the start to the last square's end: the page keeps the square's corner clear.
  bool pulsing(Nanos now) const { return !all_.empty() && now < all_.back() + kShown; }
  static constexpr Nanos kShown = 100'000'000;  //!< how long each square shows

  static constexpr Nanos kDoneShownFor = 10 * kNanosPerSecond;

 private:
  std::vector<Nanos> instants_;  //!< still to come or on screen
  std::vector<Nanos> all_;       //!< every instant of the test, for its progress
  std::vector<audio::PhotodiodeSquare> squares_;  //!< all_'s, with their first present
};

}  // namespace mallet::app
