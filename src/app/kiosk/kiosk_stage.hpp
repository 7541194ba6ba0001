#pragma once
// What the kiosk plays with, made from the scene and the settings and made anew whole on a
// reload (SIGHUP, the operator page's S): the audio rig and its device, the renderer, the
// main thread's strike route, the input chosen (input_choice.hpp) with its reading threads,
// the calibration in use, and the visitor micro-study's protocol.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/kiosk/link_watch.hpp"
#include "app/kiosk/metrics_file.hpp"
#include "app/strike/mouse_pointer.hpp"
#include "app/strike/remote_pointer.hpp"
#include "app/strike/strike_route.hpp"
#include "audio/audio_setup.hpp"
#include "audio/portaudio_output.hpp"
#include "core/app_config.hpp"
#include "core/calibration_file.hpp"
#include "core/kiosk_states.hpp"
#include "core/scene.hpp"
#include "core/study/study_protocol.hpp"
#include "input/camera/camera_device.hpp"
#include "input/evdev/evdev_mouse.hpp"
#include "input/wiimote/hid_transport.hpp"
#include "input/wiimote/replay_transport.hpp"
#include "input/wiimote/wiimote_device.hpp"
#include "render/scene_renderer.hpp"

namespace mallet::app {

//! Everything that depends on the scene and the settings, rebuilt on a reload.
struct KioskStage {
  AppConfig config;
  //! The scene as its file lays it out (landscape): the visitor study's base, and what a
  //! new layout starts from.
  Scene file_scene;
  //! The scene as the screen shows it: file_scene laid out for the screen's shape
  //! (core/scene_layout.hpp), what the routes, the renderer and the ghost play.
  Scene scene;
  double laid_out_for_aspect = 0;  //!< the screen's width over height when it was laid out
  //! Strikes by target and material, recorded by every route of this stage (any thread).
  std::unique_ptr<StrikeTally> tally;
  std::string settings_line;                          //!< where the settings came from
  std::vector<std::filesystem::path> scene_choices;  //!< the usable [scenes] choices (S)
  std::vector<std::string> problems;                  //!< drop-ins and scene choices refused
  //! What this stage's build found of the visitor study: why it is off, or which of its
  //! languages it cannot show. Kept apart from `problems`, which a new layout builds on.
  std::vector<std::string> visitor_problems;
  //! The start's settings were refused and this stage runs on a fallback: the line that says
  //! so (kiosk_setup.hpp); empty once a reload loads the operator's settings.
  std::string refused;
  audio::AudioRig rig;
  std::unique_ptr<audio::PortAudioOutput> output;
  std::string audio_status;
  std::unique_ptr<render::SceneRenderer> renderer;
  //! The main thread's strike route: the ghost, and the mouse when the window system reads it.
  std::unique_ptr<StrikeRoute> route;
  InputSource source = InputSource::mouse;
  std::string input_why;             //!< how the source was chosen, for the operator page
  std::optional<Calibration> calibration;  //!< the remote's camera → screen map in use
  std::string calibration_status;
  std::string calibration_status_sensitivity;  //!< what the last calibration's tuner chose
  // The Wii Remote (or a recording played as one): its reading thread feeds `remote`,
  // which posts strikes to the engine. The device is declared last so that it (and its
  // thread) goes first.
  std::unique_ptr<input::wiimote::ReplayFinder> replay;
  std::unique_ptr<RemotePointer> remote;
  std::unique_ptr<input::wiimote::WiimoteDevice> device;
  //! Or a V4L2 camera as the IR tracker ([input] source = "camera"), feeding `remote` the
  //! same way; at most one of `device` and `camera` is set.
  std::unique_ptr<input::camera::CameraDevice> camera;
  //! The settings the camera's strike route runs on: the stage's, with contact prediction
  //! tuned for the camera (core/camera_prediction.hpp). `remote` holds it by reference.
  std::optional<AppConfig> camera_route_config;
  LinkWatch link;  //!< the IR tracker's link as the main loop last saw it
  bool checked_calibration = false;  //!< against the first connected remote's identity
  // The mouse read at its source (input.mouse = auto | evdev): its reading thread feeds
  // `mouse`, which posts strikes itself. Without it the window system's cursor events
  // feed the main thread's route. The source is declared last so that its thread goes first.
  std::string mouse_line;  //!< how the mouse is read, for the log and the operator page
  std::unique_ptr<MousePointer> mouse;
  std::unique_ptr<input::evdev::EvdevMouse> evdev;
  //! [study] visitor_protocol, loaded against this scene (none: off, or it did not load).
  std::optional<study::StudyProtocol> visitor;
};

}  // namespace mallet::app
