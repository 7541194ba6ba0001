#include "core/config/app_config_loader.hpp"

#include "core/config/toml_reader.hpp"

namespace mallet::config {

namespace {

AppConfig read(const toml::table& root, const std::string& file) {
  AppConfig c;
  TableReader top(root, file);
  if (auto t = top.optional_table("contact")) {
    c.contact.rearm_height_m = t->number_or("rearm_height_m", c.contact.rearm_height_m);
    t->require_non_negative("rearm_height_m", c.contact.rearm_height_m);
    c.contact.min_impact_speed_m_per_s =
        t->number_or("min_impact_speed_m_per_s", c.contact.min_impact_speed_m_per_s);
    t->require_non_negative("min_impact_speed_m_per_s", c.contact.min_impact_speed_m_per_s);
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
    t->finish();
  }
  if (auto t = top.optional_table("actuator")) {
    c.actuator.gain = t->number_or("gain", c.actuator.gain);
    t->require_range("gain", c.actuator.gain, 0.0, 10.0);
    c.actuator.soft_clip_knee = t->number_or("soft_clip_knee", c.actuator.soft_clip_knee);
    t->require_range("soft_clip_knee", c.actuator.soft_clip_knee, 0.1, 0.99);
    t->finish();
  }
  if (auto t = top.optional_table("audio")) {
    c.audio.sample_rate_hz =
        static_cast<int>(t->integer_or("sample_rate_hz", c.audio.sample_rate_hz));
    t->require_range("sample_rate_hz", c.audio.sample_rate_hz, 8000, 384000);
    AudioConfig& a = c.audio;
    a.device = t->string_or("device", a.device);
    a.frames_per_buffer = static_cast<int>(t->integer_or("frames_per_buffer", a.frames_per_buffer));
    t->require_range("frames_per_buffer", a.frames_per_buffer, 16, 8192);
    a.suggested_latency_ms = t->number_or("suggested_latency_ms", a.suggested_latency_ms);
    t->require_range("suggested_latency_ms", a.suggested_latency_ms, 0, 1000);
    a.schedule_ahead_ms = t->number_or("schedule_ahead_ms", a.schedule_ahead_ms);
    t->require_range("schedule_ahead_ms", a.schedule_ahead_ms, 0, 1000);
    a.max_voices = static_cast<int>(t->integer_or("max_voices", a.max_voices));
    t->require_range("max_voices", a.max_voices, 1, 4096);
    a.volume = t->number_or("volume", a.volume);
    t->require_range("volume", a.volume, 0, 4);
    const std::string route = t->string_or("acoustic", "modal");
    if (route == "modal") a.acoustic = AcousticRoute::modal;
    else if (route == "midi") a.acoustic = AcousticRoute::midi;
    else t->fail("acoustic", "expected \"modal\" or \"midi\", got \"" + route + "\"");
    a.soundfont = t->string_or("soundfont", a.soundfont);
    if (auto r = t->optional_table("routing")) {
      AudioRouting& routing = c.audio.routing;
      routing.channels = static_cast<int>(r->integer_or("channels", routing.channels));
      r->require_range("channels", routing.channels, 1, 64);
      routing.acoustic = static_cast<int>(r->integer_or("acoustic", routing.acoustic));
      r->require_range("acoustic", routing.acoustic, 0, routing.channels - 1);
      routing.actuator = static_cast<int>(r->integer_or("actuator", routing.actuator));
      r->require_range("actuator", routing.actuator, 0, routing.channels - 1);
      r->finish();
    }
    t->finish();
  }
  top.finish();
  return c;
}

}  // namespace

AppConfig load_app_config(const std::filesystem::path& path) {
  return read(parse_file(path), path.string());
}

AppConfig parse_app_config(std::string_view text, const std::string& name) {
  return read(parse_text(text, name), name);
}

}  // namespace mallet::config
