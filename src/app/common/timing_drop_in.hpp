#pragma once
// What the latency measurements write into the settings: `mallet calibrate latency --loopback
// --save` the sound card's [timing] audio_output_latency_ms (in the settings' drop-in folder),
// the latency test's photodiode (confirmed on the operator page) the display's [timing]
// display_latency_ms (in the state folder's measured drop-ins, which the settings merge:
// settings_source.hpp). Each is a drop-in of its own, read at the kiosk's next reload, so that
// either can be measured again without the other.
#include <filesystem>
#include <string>

#include "core/display_latency_record.hpp"

namespace mallet::app {

inline constexpr const char* kOutputLatencyDropIn = "60-measured-latency.toml";
inline constexpr const char* kDisplayLatencyDropIn = "61-measured-display-latency.toml";

//! Writes `drop_in_dir`/`name` atomically: `why` as its comment, then [timing] `key` = `value`.
//! Returns its path.
std::filesystem::path write_timing_drop_in(const std::filesystem::path& drop_in_dir, const char* name,
                                           const std::string& why, const char* key, double value);

//! Keeps what the photodiode measured in the state folder (display_latency.toml) and, when
//! the operator confirmed it (`m.saved`), writes it as [timing] display_latency_ms in the
//! state folder's measured drop-ins (measured_settings_dir(), kDisplayLatencyDropIn: the
//! kiosk's service may not write /etc). Returns the drop-in's path, or empty when not confirmed.
std::filesystem::path keep_display_latency(const DisplayLatencyMeasurement& m);

}  // namespace mallet::app
