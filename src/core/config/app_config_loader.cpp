#include "core/config/app_config_loader.hpp"

#include <algorithm>
#include <iterator>

#include <fmt/format.h>

#include "core/config/app_config_table.hpp"
#include "core/config/toml_reader.hpp"
#include "core/operator_knobs.hpp"
#include "core/present_clock.hpp"
#include "core/quality.hpp"
#include "core/visitor_language.hpp"

namespace mallet::config {

AppConfig read_app_config(const toml::table& root, const std::string& file) {
  AppConfig c;
  TableReader top(root, file);
  // The preset first: it only sets defaults, so every knob the file names overrides it.
  apply_quality(top.choice_or("quality", kQualityNames, c.quality), c);
  if (auto t = top.optional_table("contact")) {
    c.contact.rearm_height_m = t->non_negative_or("rearm_height_m", c.contact.rearm_height_m);
    c.contact.min_impact_speed_m_per_s =
        t->non_negative_or("min_impact_speed_m_per_s", c.contact.min_impact_speed_m_per_s);
    c.contact.max_impact_speed_m_per_s =
        t->number_or("max_impact_speed_m_per_s", c.contact.max_impact_speed_m_per_s);
    if (!(c.contact.max_impact_speed_m_per_s > c.contact.min_impact_speed_m_per_s))
      t->fail("max_impact_speed_m_per_s", "must be greater than min_impact_speed_m_per_s");
    t->finish();
  }
  if (auto t = top.optional_table("visual")) {
    const std::string bounce = t->string_or("bounce", "signed");
    if (bounce == "signed") c.bounce = BounceMode::signed_eq1;
    else if (bounce == "rectified") c.bounce = BounceMode::rectified;
    else t->fail("bounce", "expected \"signed\" or \"rectified\", got \"" + bounce + "\"");
    c.note_names = t->boolean_or("note_names", c.note_names);
    t->finish();
  }
  if (auto t = top.optional_table("kiosk")) {
    c.language = t->string_or("language", c.language);
    if (!is_visitor_language(c.language)) load_dropin_catalogues();  // one dropped in since
    if (!is_visitor_language(c.language))
      t->fail("language", "\"" + c.language + "\" has no catalogue; expected one of " + visitor_languages_text());
    t->finish();
  }
  if (auto t = top.optional_table("fonts")) {
    for (const std::string& language : t->keys()) {
      if (!is_language_code(language))
        t->fail(language, "not a language code (two or three lowercase letters, as \"ar\" or \"yue\")");
      const std::string family = t->string_or(language, "");
      if (family.empty()) t->fail(language, "names no font family");
      c.render.fonts[language] = family;
    }
    t->finish();
  }
  if (auto t = top.optional_table("actuator")) {
    t->read("gain", c.actuator.gain, kGainKnob.lo, kGainKnob.hi);  // the operator page's range too
    t->read("soft_clip_knee", c.actuator.soft_clip_knee, kMinSoftClipKnee, kMaxSoftClipKnee);
    c.actuator.equalize = t->boolean_or("equalize", c.actuator.equalize);
    t->finish();
  }
  if (auto t = top.optional_table("audio")) {
    t->read("sample_rate_hz", c.audio.sample_rate_hz, 8000, 384000);
    AudioConfig& a = c.audio;
    a.device = t->string_or("device", a.device);
    t->read("frames_per_buffer", a.frames_per_buffer, 16, 8192);
    t->read("suggested_latency_ms", a.suggested_latency_ms, 0, 1000);
    t->read("min_latency_ms", a.min_latency_ms, 0, 1000);
    t->read("grow_after_underruns", a.grow_after_underruns, 0, 1000000);
    t->read("underrun_window_ms", a.underrun_window_ms, 10, 3600000);
    t->read("max_latency_ms", a.max_latency_ms, 1, 2000);
    if (a.max_latency_ms < a.min_latency_ms)
      t->fail(t->has("max_latency_ms") ? "max_latency_ms" : "min_latency_ms",
              "max_latency_ms must not be below min_latency_ms");
    t->read("schedule_ahead_ms", a.schedule_ahead_ms, 0, 1000);
    t->read("max_voices", a.max_voices, 1, 4096);
    t->read("max_modes", a.max_modes, 1, kMaxModalModes);
    t->read("volume", a.volume, kVolumeKnob.lo, kVolumeKnob.hi);  // the operator page's range too
    const std::string route = t->string_or("acoustic", "modal");
    if (route == "modal") a.acoustic = AcousticRoute::modal;
    else if (route == "midi") a.acoustic = AcousticRoute::midi;
    else t->fail("acoustic", "expected \"modal\" or \"midi\", got \"" + route + "\"");
    a.soundfont = t->string_or("soundfont", a.soundfont);
    if (auto r = t->optional_table("routing")) {
      AudioRouting& routing = c.audio.routing;
      r->read("channels", routing.channels, 1, 64);
      r->read("acoustic", routing.acoustic, 0, routing.channels - 1);
      r->read("actuator", routing.actuator, 0, routing.channels - 1);
      r->finish();
    }
    t->finish();
  }
  if (auto t = top.optional_table("pointer")) {
    OneEuroConfig& p = c.pointer;
    t->read("min_cutoff_hz", p.min_cutoff_hz, 0.01, 100);
    t->read("beta_per_m", p.beta_per_m, 0, 1e6);
    t->read("d_cutoff_hz", p.d_cutoff_hz, 0.01, 100);
    p.derivative_from_raw = t->boolean_or("derivative_from_raw", p.derivative_from_raw);
    t->finish();
  }
  if (auto t = top.optional_table("tracking")) {
    IrTrackerConfig& k = c.tracking;
    t->read("max_speed_px_per_s", k.max_speed_px_per_s, 1, 1e6);
    t->read("jump_slack_px", k.jump_slack_px, 0, 1024);
    t->read("reacquire_after_frames", k.reacquire_after_frames, 1, 1000);
    t->read("lost_after_ms", k.lost_after_ms, 1, 60000);
    t->finish();
  }
  if (auto t = top.optional_table("wiimote")) {
    WiimoteConfig& w = c.wiimote;
    w.device = t->string_or("device", w.device);
    const std::string mode = t->string_or("ir_mode", "extended");
    if (mode == "extended") w.ir_mode = IrMode::extended;
    else if (mode == "basic") w.ir_mode = IrMode::basic;
    else t->fail("ir_mode", "expected \"extended\" or \"basic\", got \"" + mode + "\"");
    w.sensitivity = t->string_or("sensitivity", w.sensitivity);
    if (!find_sensitivity(w.sensitivity))
      t->fail("sensitivity", "unknown preset \"" + w.sensitivity + "\" (known: " + sensitivity_names() + ")");
    w.rumble_on_impact = t->boolean_or("rumble_on_impact", w.rumble_on_impact);
    t->read("rumble_ms", w.rumble_ms, 1, 1000);
    t->read("silence_timeout_ms", w.silence_timeout_ms, 100, 60000);
    t->read("reconnect_min_ms", w.reconnect_min_ms, 10, 60000);
    t->read("reconnect_max_ms", w.reconnect_max_ms, w.reconnect_min_ms, 600000);
    t->finish();
  }
  if (auto t = top.optional_table("camera")) {
    CameraConfig& k = c.camera;
    k.device = t->string_or("device", k.device);
    if (k.device.empty()) t->fail("device", "empty: give \"auto\", a /dev/video* node or a part of the camera's name");
    t->read("width", k.width, 16, 8192);
    t->read("height", k.height, 16, 8192);
    t->read("rate_hz", k.rate_hz, 1, 1000);
    t->read("exposure_us", k.exposure_us, 0, 1000000);
    if (k.exposure_us > 0 && k.exposure_us * k.rate_hz > 1e6)
      t->fail(t->has("exposure_us") ? "exposure_us" : "rate_hz",
              fmt::format("exposure_us {} is longer than one frame at rate_hz {:g} ({:.0f} µs)", k.exposure_us,
                          k.rate_hz, 1e6 / k.rate_hz));
    t->read("gain", k.gain, -1, 1000000);
    k.format = t->string_or("format", k.format);
    if (std::find(std::begin(kCameraFormats), std::end(kCameraFormats), k.format) == std::end(kCameraFormats))
      t->fail("format", "expected \"auto\", \"grey\", \"yuyv\" or \"mjpeg\", got \"" + k.format + "\"");
    t->finish();
  }
  if (auto t = top.optional_table("input")) {
    InputConfig& i = c.input;
    i.source = t->string_or("source", i.source);
    if (i.source != "auto" && i.source != "wiimote" && i.source != "camera" && i.source != "mouse" &&
        i.source != "replay")
      t->fail("source",
              "expected \"auto\", \"wiimote\", \"camera\", \"mouse\" or \"replay\", got \"" + i.source + "\"");
    i.replay_file = t->string_or("replay_file", i.replay_file);
    if (i.source == "replay" && i.replay_file.empty())
      t->fail("source", "\"replay\" needs replay_file (a `mallet wiimote monitor --record` file)");
    if (!i.replay_file.empty() && std::filesystem::path(i.replay_file).is_relative())
      i.replay_file = (std::filesystem::path(file).parent_path() / i.replay_file).string();
    i.mouse = t->string_or("mouse", i.mouse);
    if (i.mouse != "auto" && i.mouse != "evdev" && i.mouse != "window")
      t->fail("mouse", "expected \"auto\", \"evdev\" or \"window\", got \"" + i.mouse + "\"");
    i.mouse_device = t->string_or("mouse_device", i.mouse_device);
    t->finish();
  }
  if (auto t = top.optional_table("timing")) {
    TimingConfig& g = c.timing;
    g.align = t->choice_or("align", kCueAlignNames, g.align);
    t->read("display_latency_ms", g.display_latency_ms, 0, 200);
    g.photodiode_channel = static_cast<int>(t->integer_or("photodiode_channel", g.photodiode_channel));
    t->require_range("photodiode_channel", g.photodiode_channel, 0, 64);
    g.photodiode_input = t->string_or("photodiode_input", g.photodiode_input);
    double& audio = c.audio.output_latency_ms;
    audio = t->number_or("audio_output_latency_ms", audio);
    if (audio >= 0) t->require_range("audio_output_latency_ms", audio, 0, 500);
    const std::string confidence = t->string_or("predict_confidence", g.predict_confidence);
    const double horizon = t->number_or("predict_horizon_ms", g.predict.horizon_ms);
    t->require_range("predict_horizon_ms", horizon, 0, 50);
    const double clearance = t->number_or("predict_clearance_m", g.predict.clearance_m);
    t->require_range("predict_clearance_m", clearance, 0, 0.05);
    if (const std::optional<PredictionConfig> level = prediction_confidence(confidence)) g.predict = *level;
    else t->fail("predict_confidence", "expected \"eager\", \"balanced\" or \"exact\", got \"" + confidence + "\"");
    g.predict_confidence = confidence;
    g.predict.horizon_ms = horizon;
    g.predict.clearance_m = clearance;
    t->finish();
  }
  if (auto t = top.optional_table("attract")) {
    AttractConfig& a = c.attract;
    t->read("idle_after_s", a.idle_after_s, 1, 86400);
    t->read("volume", a.volume, 0, 1);
    if (t->has("languages")) a.languages = t->strings("languages");
    for (const std::string& l : a.languages)
      if (!is_visitor_language(l) && (load_dropin_catalogues(), !is_visitor_language(l)))
        t->fail("languages", "\"" + l + "\" has no catalogue; expected some of " + visitor_languages_text());
    t->read("language_every_s", a.language_every_s, 1, 3600);
    t->finish();
  }
  if (auto t = top.optional_table("render")) {
    RenderConfig& r = c.render;
    r.present_mode = t->choice_or("present_mode", kPresentPacingNames, r.present_mode);
    r.msaa = t->string_or("msaa", r.msaa);
    if (r.msaa != "auto" && r.msaa != "1" && r.msaa != "2" && r.msaa != "4" && r.msaa != "8")
      t->fail("msaa", "expected \"auto\", \"1\", \"2\", \"4\" or \"8\", got \"" + r.msaa + "\"");
    r.shadow = t->boolean_or("shadow", r.shadow);
    r.device = t->string_or("device", r.device);
    t->read("monitor", r.monitor, 0, 15);
    t->read("max_fps", r.max_fps, 0, 1000);
    r.software_present = t->choice_or("software_present", kSoftwarePresentNames, r.software_present);
    t->finish();
  }
  if (auto t = top.optional_table("scenes")) {
    ScenesConfig& sc = c.scenes;
    sc.start = t->string_or("start", sc.start);
    if (t->has("start")) sc.start_at = t->place("start");
    if (t->has("choices")) sc.choices = t->strings("choices"), sc.choices_at = t->place("choices");
    for (const std::string& f : sc.choices)
      if (f.empty()) t->fail("choices", "a scene file name is empty");
    if (sc.start.empty()) t->fail("start", "must name a scene file");
    t->finish();
  }
  if (auto t = top.optional_table("metrics")) {
    MetricsConfig& m = c.metrics;
    m.textfile = t->string_or("textfile", m.textfile);
    if (!m.textfile.empty() && m.textfile.back() == '/')
      t->fail("textfile", "names a folder; expected a file such as \"" + m.textfile + "mallet.prom\"");
    if (!m.textfile.empty() && std::filesystem::path(m.textfile).is_relative())
      m.textfile = (std::filesystem::path(file).parent_path() / m.textfile).string();
    t->read("interval_s", m.interval_s, 1, 3600);
    t->finish();
  }
  if (auto t = top.optional_table("study")) {
    StudyConfig& st = c.study;
    const auto relative_to_file = [&](const std::string& p) {
      return p.empty() || std::filesystem::path(p).is_absolute() ? p
                                                                  : (std::filesystem::path(file).parent_path() / p).string();
    };
    st.visitor_protocol = relative_to_file(t->string_or("visitor_protocol", st.visitor_protocol));
    st.visitor_protocol_at = t->place("visitor_protocol");
    t->read("offer_every_s", st.offer_every_s, 10, 86400);
    t->read("offer_for_s", st.offer_for_s, 5, 600);
    st.results_dir = relative_to_file(t->string_or("results_dir", st.results_dir));
    t->finish();
  }
  top.finish();
  return c;
}

AppConfig load_app_config(const std::filesystem::path& path) {
  return read_app_config(parse_file(path), path.string());
}

AppConfig parse_app_config(std::string_view text, const std::string& name) {
  return read_app_config(parse_text(text, name), name);
}

}  // namespace mallet::config
