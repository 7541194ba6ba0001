#pragma once
// The paper's acoustic route: position → MIDI note, speed → MIDI velocity, played by
// FluidSynth with a General MIDI soundfont (GM Xylophone, program 13; Glockenspiel,
// program 9; from Debian's timgm6mb-soundfont by default) and rendered inside our own
// audio callback, so each note starts on its impact's own sample like the actuator.
// FluidSynth's own driver would add its 16×64-frame periods (≈21 ms) of latency.
//
// Construction (loading the soundfont) happens before audio runs; note_on() and
// render() are called only from the audio thread. The synth is created without
// FluidSynth's API mutex, since no other thread touches it after construction.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "audio/engine.hpp"

typedef struct _fluid_hashtable_t fluid_settings_t;
typedef struct _fluid_synth_t fluid_synth_t;

namespace mallet::audio {

class FluidSynthRoute final : public ExternalAcoustic {
 public:
  //! Throws std::runtime_error naming the file and the Debian package when the
  //! soundfont is missing or unreadable. `programs[i]` is the GM program (0-based) of
  //! instrument i; each instrument gets its own MIDI channel.
  FluidSynthRoute(const std::string& soundfont, int sample_rate_hz, const std::vector<int>& programs,
                  double gain = 2.0);
  ~FluidSynthRoute() override;
  FluidSynthRoute(const FluidSynthRoute&) = delete;
  FluidSynthRoute& operator=(const FluidSynthRoute&) = delete;

  //! MIDI velocity for a strike speed: 100·v / 2 m/s, clamped to 1..127.
  static int velocity_for(double speed_m_per_s);

  void note_on(int instrument, int note, double speed_m_per_s) override;
  void render(double* out, int frames) override;

 private:
  struct NoteOff {
    std::int64_t at = 0;
    int channel = 0, note = 0;
    bool pending = false;
  };
  void render_span(double* out, int frames);

  fluid_settings_t* settings_ = nullptr;
  fluid_synth_t* synth_ = nullptr;
  int sample_rate_;
  int channels_;
  std::int64_t position_ = 0;
  std::array<NoteOff, 256> offs_{};
  std::vector<float> left_, right_;
};

}  // namespace mallet::audio
