#pragma once
// The kiosk's settings (config/mallet.toml). The defaults here are the shipped file's
// values; a test keeps the two equal.
#include <map>
#include <string>
#include <vector>

#include "core/file_error.hpp"
#include "core/ir_camera_settings.hpp"
#include "core/ir_tracker.hpp"
#include "core/mallet.hpp"
#include "core/modal_preset.hpp"
#include "core/contact_predictor.hpp"
#include "core/enum_names.hpp"
#include "core/one_euro_filter.hpp"
#include "core/present_clock.hpp"
#include "core/visual_vibration.hpp"

namespace mallet {

struct ActuatorConfig {
  double gain = 0.2;             //!< the paper's amplifier knob: output = gain·A·v·e^(−Bt)·sin
  double soft_clip_knee = 0.9;   //!< the output limiter's threshold: identity below (audio/peak_limiter.hpp)
  //! Apply the measured chain's inverse (actuator_eq.toml in the state folder, written by
  //! `mallet calibrate actuator`) to the actuator channel; nothing happens without that file.
  bool equalize = true;
};

//! soft_clip_knee's range in the settings: the top stays under the output limiter's
//! ceiling (0.98, audio/peak_limiter.hpp, which checks it), so the shoulder keeps room.
inline constexpr double kMinSoftClipKnee = 0.1, kMaxSoftClipKnee = 0.95;

//! Which output channel carries what. Both on one channel = mono mix (no actuator fitted).
struct AudioRouting {
  int channels = 2;
  int acoustic = 0;
  int actuator = 1;
};

//! Where the speaker's note comes from.
enum class AcousticRoute {
  modal,  //!< built-in modal bar synthesis (default)
  midi,   //!< the paper's route: FluidSynth with a General MIDI soundfont
};

struct AudioConfig {
  int sample_rate_hz = 48000;
  std::string device;               //!< PortAudio output: name substring or index; empty = default
  int frames_per_buffer = 64;
  double suggested_latency_ms = 0;  //!< 0 = the device's default low latency
  //! The output buffer is never asked for less than this (PortAudio's suggested latency),
  //! whatever suggested_latency_ms or the device's default says: a few-period ALSA buffer
  //! underruns whenever the machine is busy (src/audio/portaudio_output.hpp, UNDERRUNS).
  double min_latency_ms = 10;
  //! This many output underruns within underrun_window_ms reopen the device with twice the
  //! latency, up to max_latency_ms, while the kiosk plays on; 0 = never.
  int grow_after_underruns = 4;
  double underrun_window_ms = 5000;
  double max_latency_ms = 100;      //!< the ceiling of that growth
  double schedule_ahead_ms = 0;     //!< 0 = as soon as possible; > 0 = constant latency, no jitter
  //! From a frame leaving the callback to it being heard; < 0: the device's own report
  //! (PortAudio's outputLatency). Set by [timing] audio_output_latency_ms (measured, key T).
  double output_latency_ms = -1;
  int max_voices = 64;
  int max_modes = kMaxModalModes;   //!< modes sounding per bar (a quality knob; see core/quality.hpp)
  double volume = 0.8;              //!< speaker channel gain (the operator's volume)
  AcousticRoute acoustic = AcousticRoute::modal;
  std::string soundfont = "/usr/share/sounds/sf2/TimGM6mb.sf2";  //!< for the midi route
  AudioRouting routing;
};

//! [wiimote]: the remote whose IR camera watches the stick's LED, and how the link to it
//! is kept alive.
struct WiimoteConfig {
  std::string device;  //!< a part of the hidraw path or of the serial (Bluetooth address); empty = the first remote
  IrMode ir_mode = IrMode::extended;                          //!< extended carries each dot's size
  std::string sensitivity = std::string(kDefaultSensitivity);  //!< a name from kSensitivityPresets
  bool rumble_on_impact = false;  //!< a short rumble pulse per strike (when the visitor holds the remote)
  double rumble_ms = 40;
  double silence_timeout_ms = 3000;  //!< no report for this long = the remote is gone: reconnect
  double reconnect_min_ms = 500;     //!< first wait between connection attempts, doubling ...
  double reconnect_max_ms = 5000;    //!< ... up to this
};

//! [camera]: a V4L2 camera (a UVC webcam or a global-shutter USB camera behind an 850 nm
//! filter) as the IR tracker, with [input] source = "camera" (src/input/camera/).
struct CameraConfig {
  //! "auto" (the first video capture device under /dev), a node (/dev/video2, or a stable
  //! /dev/v4l/by-id/... link), or a part of the camera's name as `mallet camera list` shows it.
  std::string device = "auto";
  int width = 640;         //!< pixels asked for; the driver may give the nearest size it has
  int height = 480;
  double rate_hz = 120;    //!< frames a second asked for; the achieved rate is shown and measured
  //! Exposure in µs, set by hand (the LED is bright: short exposures freeze the stroke and
  //! darken everything else); 0 = the camera's automatic exposure. Below one frame's time.
  int exposure_us = 500;
  int gain = -1;           //!< the camera's own gain units (`mallet camera list`); -1 = leave it
  std::string format = "auto";  //!< "auto" (grey, else yuyv, else mjpeg), "grey", "yuyv" or "mjpeg"
};
inline constexpr const char* kCameraFormats[] = {"auto", "grey", "yuyv", "mjpeg"};

//! [input]: where the mallet's position comes from.
struct InputConfig {
  //! "auto": the Wii Remote when one is found at start-up, else the mouse (said on screen);
  //! "wiimote": the Wii Remote only (none found: the attract mode and a hint, looked for
  //! forever); "camera": a V4L2 camera ([camera]), looked for forever as the remote is;
  //! "mouse": the mouse only (a test bench, or no remote at all); "replay":
  //! replay_file, a `mallet wiimote monitor --record` file, played as a live remote (looping).
  std::string source = "auto";
  std::string replay_file;  //!< for "replay"; relative to the settings file's folder
  //! How the mouse is read: "auto" (its event node through evdev, at the device's own
  //! rate, stamped by the kernel; the window system's events when no node can be opened),
  //! "evdev" (the node; a warning when it cannot be opened, and the window system's events
  //! keep the kiosk playable) or "window" (the window system's cursor events only).
  std::string mouse = "auto";
  std::string mouse_device;  //!< an evdev node (/dev/input/eventN); empty = the first mouse
};

//! [timing] align: when the actuator and the note are heard.
enum class CueAlign {
  asap,     //!< as soon as the strike is known (or at its predicted contact)
  picture,  //!< together with the first frame that shows the bounce
};
inline constexpr EnumNames<CueAlign, 2> kCueAlignNames{{{CueAlign::asap, "asap"}, {CueAlign::picture, "picture"}}};

const char* to_string(CueAlign a);

//! [timing]: when the three cues of a strike reach the visitor (src/app/strike_route.hpp).
struct TimingConfig {
  CueAlign align = CueAlign::asap;
  double display_latency_ms = 0;        //!< from a present to light on the panel (measured, key T)
  //! A photodiode on the screen's top-left corner, on input channel photodiode_channel (from
  //! 1; 0 = none) of photodiode_input ("" = the default input): the latency test (T) then
  //! measures display_latency_ms itself (app/kiosk/photodiode_latency.hpp).
  int photodiode_channel = 0;
  std::string photodiode_input;
  // [timing] audio_output_latency_ms is AudioConfig::output_latency_ms (the device's clock).
  //! Contact prediction ([timing] predict_horizon_ms, 0 = off; predict_confidence names the
  //! set of tests a prediction must pass; predict_clearance_m): see core/contact_predictor.hpp.
  std::string predict_confidence = "balanced";
  PredictionConfig predict = prediction_balanced();
};

//! [attract]: the attract mode that plays when nobody is there.
struct AttractConfig {
  double idle_after_s = 45.0;  //!< no real movement for this long → the ghost player plays
  double volume = 0.5;         //!< the speaker's volume while it plays (a fraction of audio.volume)
  //! The visitor languages it shows in turn, each for language_every_s (empty: [kiosk]
  //! language only). A visitor who starts playing keeps the one on the screen then.
  std::vector<std::string> languages;
  double language_every_s = 15.0;
};

//! How a CPU rasteriser's frames (lavapipe) reach an X11 window: only the pixels that
//! changed, put into it (render/x11_image_put.hpp), or whole through Vulkan's swapchain.
enum class SoftwarePresent { changes, swapchain };
inline constexpr EnumNames<SoftwarePresent, 2> kSoftwarePresentNames{
    {{SoftwarePresent::changes, "changes"}, {SoftwarePresent::swapchain, "swapchain"}}};

//! [render]: the screen. Values are names so the core stays free of Vulkan.
struct RenderConfig {
  PresentPacing present_mode = PresentPacing::fifo;  //!< fifo (vsync), mailbox or immediate; fifo where not offered
  std::string msaa = "auto";          //!< auto (CPU rasteriser: 4 for the cached instruments, 1 per frame; GPU: 4), 1, 2, 4 or 8
  bool shadow = true;                 //!< the mallet's analytic cast shadow
  std::string device;                 //!< a part of the Vulkan device's name; empty = the best one
  int monitor = 0;                    //!< which monitor the fullscreen kiosk uses (GLFW's order)
  //! The frame budget (core/frame_pacer.hpp), frames a second: 0 = the display's refresh;
  //! never above it.
  double max_fps = 0;
  SoftwarePresent software_present = SoftwarePresent::changes;
  //! [fonts]: language → the font family its text is set in, where fontconfig's choice is
  //! wrong ("am" = "Noto Sans Ethiopic"); a language not named: the Noto family of its script.
  std::map<std::string, std::string> fonts;
};

//! [scenes]: which scene the kiosk shows, and which the operator page can switch to. File
//! names are relative to the scenes/ folder next to the settings file.
struct ScenesConfig {
  std::string start = "percussion.toml";
  std::vector<std::string> choices{"percussion.toml", "texture.toml", "wall.toml"};
  //! Where the settings named them (empty file: the built-in defaults), so that a scene file
  //! that is missing is reported against the line that names it.
  FilePlace start_at, choices_at;
};

//! [metrics]: the kiosk's metrics in Prometheus' text format (core/kiosk_metrics.hpp), for
//! node_exporter's textfile collector.
struct MetricsConfig {
  std::string textfile;      //!< the file to replace; empty = off; relative: to the settings file's folder
  double interval_s = 15.0;  //!< how often it is replaced (node_exporter's default scrape is 15 s)
};

//! [study]: the visitor micro-study the kiosk offers (app/visitor_study.hpp).
struct StudyConfig {
  //! A study protocol with a [visitor] table; empty = off (the one key that switches it
  //! off). Relative: to the settings file's folder.
  std::string visitor_protocol;
  FilePlace visitor_protocol_at;  //!< where it was set (a protocol that does not load is reported there)
  double offer_every_s = 300.0;   //!< the attract screen offers it this often...
  double offer_for_s = 30.0;      //!< ...for this long
  //! The visitors' results, one file a day (visitors-YYYY-MM-DD.csv); empty: the kiosk's
  //! state folder's visitor-study/. Relative: to the settings file's folder.
  std::string results_dir;
};

//! Where speed is traded for accuracy: a preset of knobs (core/quality.hpp).
enum class Quality {
  fast,      //!< frames first: an old mini-PC with software rendering
  balanced,  //!< the shipped defaults
  exact,     //!< stimuli first: a lab's perceptual study
};
inline constexpr EnumNames<Quality, 3> kQualityNames{
    {{Quality::fast, "fast"}, {Quality::balanced, "balanced"}, {Quality::exact, "exact"}}};

struct AppConfig {
  Quality quality = Quality::balanced;  //!< the preset the knobs below started from
  ContactConfig contact;
  BounceMode bounce = BounceMode::signed_eq1;
  bool note_names = false;  //!< [visual] note_names: each bar's note name on its near end
  std::string language = "en";  //!< [kiosk] language: the texts' (core/visitor_language.hpp)
  ActuatorConfig actuator;
  AudioConfig audio;
  OneEuroConfig pointer;     //!< [pointer]: the 1€ filter of the displayed cursor
  IrTrackerConfig tracking;  //!< [tracking]: which IR dot is the stick's LED
  InputConfig input;
  WiimoteConfig wiimote;
  CameraConfig camera;
  RenderConfig render;
  AttractConfig attract;
  ScenesConfig scenes;
  TimingConfig timing;
  MetricsConfig metrics;
  StudyConfig study;
};

}  // namespace mallet
