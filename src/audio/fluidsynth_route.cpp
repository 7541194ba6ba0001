#include "audio/fluidsynth_route.hpp"

#include <fluidsynth.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace mallet::audio {

namespace {
constexpr int kMaxFrames = 4096;           // matches the engine's largest block
constexpr double kNoteLengthS = 3.0;       // a struck bar is released after this
}  // namespace

FluidSynthRoute::FluidSynthRoute(const std::string& soundfont, int sample_rate_hz, const std::vector<int>& programs,
                                 double gain)
    : sample_rate_(sample_rate_hz), channels_(static_cast<int>(programs.size())) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(soundfont, ec))
    throw std::runtime_error(soundfont + ": soundfont not found (install the Debian package timgm6mb-soundfont, "
                                         "or set [audio].soundfont)");
  if (channels_ < 1 || channels_ > 16) throw std::runtime_error("midi route: 1 to 16 instruments");
  settings_ = new_fluid_settings();
  fluid_settings_setnum(settings_, "synth.sample-rate", sample_rate_hz);
  fluid_settings_setint(settings_, "synth.threadsafe-api", 0);
  fluid_settings_setnum(settings_, "synth.gain", gain);
  fluid_settings_setint(settings_, "synth.polyphony", 256);
  // No reverb or chorus: they add a ~1e-8 noise floor (FluidSynth's guard against
  // denormals) and a tail the stimuli do not have; between strikes the output is 0.
  fluid_settings_setint(settings_, "synth.reverb.active", 0);
  fluid_settings_setint(settings_, "synth.chorus.active", 0);
  synth_ = new_fluid_synth(settings_);
  if (!synth_) {
    delete_fluid_settings(settings_);
    throw std::runtime_error("midi route: FluidSynth could not be created");
  }
  const int sfont = fluid_synth_sfload(synth_, soundfont.c_str(), 1);
  if (sfont == FLUID_FAILED) {
    delete_fluid_synth(synth_);
    delete_fluid_settings(settings_);
    throw std::runtime_error(soundfont + ": not a SoundFont FluidSynth can load");
  }
  for (int ch = 0; ch < channels_; ++ch) {
    const int program = programs[static_cast<std::size_t>(ch)];
    if (fluid_synth_program_select(synth_, ch, sfont, 0, program) == FLUID_FAILED) {
      delete_fluid_synth(synth_);
      delete_fluid_settings(settings_);
      throw std::runtime_error(soundfont + ": has no General MIDI program " + std::to_string(program));
    }
  }
  left_.resize(kMaxFrames);
  right_.resize(kMaxFrames);
}

FluidSynthRoute::~FluidSynthRoute() {
  delete_fluid_synth(synth_);
  delete_fluid_settings(settings_);
}

int FluidSynthRoute::velocity_for(double speed_m_per_s) {
  if (!(speed_m_per_s > 0)) return 1;
  return static_cast<int>(std::clamp(std::lround(100.0 * speed_m_per_s / 2.0), 1L, 127L));
}

void FluidSynthRoute::note_on(int instrument, int note, double speed_m_per_s) {
  if (instrument < 0 || instrument >= channels_) return;
  // A bar struck again restarts its note, as a real bar does.
  fluid_synth_noteoff(synth_, instrument, note);
  fluid_synth_noteon(synth_, instrument, note, velocity_for(speed_m_per_s));
  NoteOff* slot = &offs_[0];
  for (NoteOff& o : offs_) {
    if (!o.pending || (o.channel == instrument && o.note == note)) {
      slot = &o;
      break;
    }
    if (o.at < slot->at) slot = &o;  // full: release the earliest sooner
  }
  *slot = {position_ + static_cast<std::int64_t>(kNoteLengthS * sample_rate_), instrument, note, true};
}

void FluidSynthRoute::render_span(double* out, int frames) {
  std::fill_n(left_.begin(), frames, 0.0f);
  std::fill_n(right_.begin(), frames, 0.0f);
  fluid_synth_write_float(synth_, frames, left_.data(), 0, 1, right_.data(), 0, 1);
  for (int i = 0; i < frames; ++i)
    out[i] += 0.5 * (static_cast<double>(left_[static_cast<std::size_t>(i)]) + right_[static_cast<std::size_t>(i)]);
  position_ += frames;
}

void FluidSynthRoute::render(double* out, int frames) {
  // Render up to each due note-off so releases also land on their own sample.
  int done = 0;
  while (done < frames) {
    std::int64_t next = position_ + std::min(frames - done, kMaxFrames);
    for (NoteOff& o : offs_) {
      if (!o.pending) continue;
      if (o.at <= position_) {
        fluid_synth_noteoff(synth_, o.channel, o.note);
        o.pending = false;
      } else {
        next = std::min(next, o.at);
      }
    }
    const int n = static_cast<int>(next - position_);
    render_span(out + done, n);
    done += n;
  }
}

}  // namespace mallet::audio
