#pragma once
// `mallet doctor`'s findings: one check a line, `ok`, `warn` or `fail`, what was found and
// how to fix it. The judgements that need no device live here (thresholds an operator can
// read in one place, tested without a kiosk); the probes that look at devices are the app's.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/actuator_eq_file.hpp"
#include "core/calibration_file.hpp"
#include "core/display_latency_record.hpp"
#include "core/latency_record.hpp"
#include "core/enum_names.hpp"

namespace mallet {

enum class CheckLevel { ok, warn, fail };
inline constexpr EnumNames<CheckLevel, 3> kCheckLevelNames{{
    {CheckLevel::ok, "ok"}, {CheckLevel::warn, "warn"}, {CheckLevel::fail, "fail"}}};
const char* to_string(CheckLevel level);

struct DoctorCheck {
  std::string name;   //!< short, stable: "vulkan", "audio", "wiimote", ... (the JSON key)
  CheckLevel level = CheckLevel::ok;
  std::string found;  //!< what was found, one line
  std::string fix;    //!< how to fix it; empty when there is nothing to do
};

//! "fail  audio        no output device ... -> fix: ..." (one line, no newline).
std::string format_check(const DoctorCheck& check);

//! 0 when no check failed, 1 otherwise (`mallet doctor`'s exit status).
int doctor_exit_status(const std::vector<DoctorCheck>& checks);

//! Free space where results and state are written: below 100 MiB fails (a study row or a
//! calibration can no longer be saved for long), below 1 GiB warns.
DoctorCheck judge_free_space(const std::string& where, std::uint64_t available_bytes);

//! The kiosk's state folder (calibration, last good settings, counters, visitor results):
//! its free space as judge_free_space, and whether it can be written. `write_problem`: why
//! a write into it failed (a probe's, or the running kiosk's last one), empty when it did not;
//! the kiosk plays on without keeping anything new, so that fails with the folder named.
DoctorCheck judge_state_folder(const std::string& where, std::uint64_t available_bytes,
                               const std::string& write_problem);

//! A GPU's render node in /dev/dri ("renderD128") and its kernel driver ("i915", "amdgpu",
//! "virtio_gpu"; empty: unknown).
struct RenderNode {
  std::string name;
  std::string driver;
};

//! The renderer of the kiosk's Wayland compositor (cage, wlroots: WLR_RENDERER) and why.
struct CompositorRenderer {
  std::string renderer;  //!< "pixman", "gles2", or what WLR_RENDERER names
  std::string reason;    //!< e.g. "no GPU render node in /dev/dri: software"
  bool from_environment = false;  //!< WLR_RENDERER was set (an operator's drop-in)
};

//! The rule mallet-session applies: a set WLR_RENDERER (an operator's drop-in) wins; else,
//! where the GPU cannot draw, wlroots' GLES2 renderer would fall back to Mesa's kms_swrast,
//! which crashes (wlroots 0.15, seen on virtio-gpu without virgl), so the session uses
//! "pixman" (the CPU): with no render node, or when Vulkan finds no GPU but only a software
//! driver such as lavapipe (`vulkan_gpu` false; a virtio-gpu without 3D has a render node
//! all the same). Otherwise "gles2" (the GPU's). `vulkan_gpu` empty: Vulkan was not asked,
//! the render node decides. `wlr_renderer` empty counts as unset, as the shell's `-z` does.
CompositorRenderer compositor_renderer(const std::vector<RenderNode>& render_nodes,
                                       const std::optional<std::string>& wlr_renderer,
                                       std::optional<bool> vulkan_gpu = std::nullopt);

//! The doctor's `compositor` line: ok, with the renderer and why; a WLR_RENDERER that asks
//! for the GPU (gles2, vulkan) where there is no render node warns.
DoctorCheck judge_compositor(const CompositorRenderer& renderer, const std::vector<RenderNode>& render_nodes);

//! The renderer: a CPU rasteriser (lavapipe) on a large display is a warning, with the frame
//! time measured at that size; above one 60 Hz refresh (16.7 ms) it fails.
DoctorCheck judge_renderer(const std::string& device, bool cpu, std::uint32_t width, std::uint32_t height,
                           double frame_ms);

//! The calibration: none (the kiosk asks for one when a remote connects), how old it is,
//! its largest reprojection error, and whether it was made with the remote connected now.
//! `problem`: why the file could not be read (empty when it was, or is absent).
DoctorCheck judge_calibration(const std::string& path, const std::optional<Calibration>& calibration,
                              const std::string& problem, std::int64_t now_unix_s,
                              const std::optional<std::string>& connected_remote);

//! The actuator calibration (actuator_eq.toml): none is fine (the actuator plays Eq. 1 as
//! computed); a file that cannot be read, or was measured at another sample rate, warns (the
//! kiosk then plays uncorrected); otherwise when it was made, with what, its identity and
//! whether the kiosk applies it ([actuator] equalize).
DoctorCheck judge_actuator_eq(const std::string& path, const std::optional<ActuatorEq>& eq, const std::string& problem,
                              std::int64_t now_unix_s, bool equalize, int sample_rate_hz);

//! The sound card's latency: when `mallet calibrate latency` last measured it (latency.toml),
//! what it found, and what [timing] audio_output_latency_ms says (`setting_ms` < 0: PortAudio's
//! own figure). Never measured is fine (ok, with how to); a setting that differs by more than
//! a millisecond from the measurement warns; a file that does not read warns.
DoctorCheck judge_latency(const std::string& path, const std::optional<LatencyMeasurement>& measured,
                          const std::string& problem, std::int64_t now_unix_s, double setting_ms);

//! The display's latency: when `mallet calibrate latency --photodiode` last measured it
//! (display_latency.toml), what it found, and what [timing] display_latency_ms says. Never
//! measured is fine (ok, with how to); a setting more than 2 ms from the measurement warns; a
//! file that does not read warns.
DoctorCheck judge_display_latency(const std::string& path, const std::optional<DisplayLatencyMeasurement>& measured,
                                  const std::string& problem, std::int64_t now_unix_s, double setting_ms);

//! Seconds since the Unix epoch of an ISO 8601 UTC time ("2025-05-01T09:30:00Z"); none if
//! it is not one.
std::optional<std::int64_t> parse_utc(const std::string& iso);

}  // namespace mallet
