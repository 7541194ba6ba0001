#pragma once
// How the kiosk chooses its input ([input] source): "mouse"; "wiimote"; "auto", a Wii Remote
// found at start-up, else the mouse; "camera", a V4L2 camera as the IR tracker, through the
// same pointer and calibration as the remote; "replay", a recording played through the
// remote's own device path. The mouse is read at its source (evdev, [input] mouse) when it can be opened,
// else from the window system's events once a frame. A remote comes with the saved
// calibration (a replay without one sees the camera's view mirrored onto the screen) and its
// reading thread strikes through its own route.
#include <optional>
#include <string>

#include "app/kiosk/kiosk_stage.hpp"
#include "core/geometry.hpp"
#include "input/clock.hpp"
#include "render/render_setup.hpp"

namespace mallet::app {

//! What the input is read with: the remotes' finder and clock, and the kiosk's window (its
//! present clock, its proportions and size); `last_cursor` is where an evdev mouse starts.
struct InputDevices {
  input::wiimote::HidDeviceFinder& finder;
  input::SteadyClock& clock;
  render::ProductWindow& window;
  std::optional<Vec2> last_cursor;
};

//! Chooses and opens the stage's input: its source, why (for the operator page), and the
//! remote's device and pointer or the mouse's. A bad replay file throws (FileError).
void choose_input(KioskStage& stage, const InputDevices& devices);

//! The IR tracker's link now (link_watch.hpp's IrLink).
IrLink ir_link(const KioskStage& stage);
//! "camera USB Camera": a calibration's owner (not its /dev/videoN, which a replug may change).
std::string camera_identity(const input::camera::CameraMode& mode);
//! Starts or stops the stage's IR tracker's reading thread (nothing without one).
void start_ir_tracker(KioskStage& stage);
void stop_ir_tracker(KioskStage& stage);

//! The input as the operator page and the doctor say it: the source, why, and its state
//! (reports a second, the LED seen, a lost mouse or remote and why).
std::string input_line(const KioskStage& stage);

}  // namespace mallet::app
