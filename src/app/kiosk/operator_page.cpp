#include "app/kiosk/operator_page.hpp"

#include <algorithm>
#include <cstdio>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "app/kiosk/doctor.hpp"
#include "app/kiosk/input_choice.hpp"
#include "core/journal.hpp"
#include "render/text_wrap.hpp"

namespace mallet::app {

bool operator_action_repeats(OperatorAction action) {
  return action == OperatorAction::volume_up || action == OperatorAction::volume_down ||
         action == OperatorAction::gain_up || action == OperatorAction::gain_down;
}

OperatorAction operator_action(int key, int mods, bool page_open) {
  if (key == GLFW_KEY_O && (mods & GLFW_MOD_CONTROL) && (mods & GLFW_MOD_ALT)) return OperatorAction::open;
  if (!page_open) return OperatorAction::none;
  switch (key) {
    case GLFW_KEY_ESCAPE: return OperatorAction::close;
    case GLFW_KEY_Q: return OperatorAction::quit;
    case GLFW_KEY_R: return OperatorAction::recalibrate;
    case GLFW_KEY_UP: return OperatorAction::volume_up;
    case GLFW_KEY_DOWN: return OperatorAction::volume_down;
    case GLFW_KEY_RIGHT: return OperatorAction::gain_up;
    case GLFW_KEY_LEFT: return OperatorAction::gain_down;
    case GLFW_KEY_M: return OperatorAction::next_material;
    case GLFW_KEY_S: return OperatorAction::next_scene;
    case GLFW_KEY_L: return OperatorAction::next_language;
    case GLFW_KEY_T: return OperatorAction::latency_test;
    case GLFW_KEY_D: return OperatorAction::doctor;
    default: return OperatorAction::none;
  }
}

void draw_operator_page(render::Overlay& o, const std::vector<std::string>& lines, bool doctor, float w, float h,
                        float clear_corner) {
  const float px = o.atlas().pixel_height();
  const float pw = std::min(w - 2 * px, px * 40);
  // Long lines (how the input is read and why, the timing figures, the key legend) wrap at
  // a semicolon, a comma, before a parenthesis or between two keys' entries onto indented
  // continuation lines, else at a space; the widths are the font's own, in every language.
  struct Break {
    const char* separator;
    std::size_t kept;    //!< its characters that end the line ("," stays, " (" goes on)
    std::size_t resume;  //!< where the continuation starts, from the separator
  };
  static constexpr Break kBreaks[] = {{"; ", 1, 2}, {", ", 1, 2}, {" (", 0, 1}, {"    ", 0, 4}};
  const render::FontAtlas& font = o.atlas();
  const float room = pw - 2 * px;
  std::vector<std::string> page;
  for (std::string text : lines) {
    if (doctor) {  // a check a line, cut to the page; the whole line is in the log
      const std::vector<std::string> cut = render::wrap_text(font, text, room - font.measure("..."));
      page.push_back(cut.size() > 1 ? cut.front() + "..." : text);
      continue;
    }
    std::string indent;
    while (font.measure(indent + text) > room) {
      std::size_t cut = std::string::npos;
      const Break* at_break = nullptr;
      for (const Break& b : kBreaks)
        for (std::size_t at = text.find(b.separator); at != std::string::npos; at = text.find(b.separator, at + 1))
          if (at > 8 && (cut == std::string::npos || at > cut) &&
              font.measure(indent + text.substr(0, at + b.kept)) <= room)
            cut = at, at_break = &b;
      if (!at_break) {  // no separator that fits: the words that do
        const std::vector<std::string> words = render::wrap_text(font, text, room - font.measure(indent));
        if (words.size() < 2) break;
        page.push_back(indent + words.front());
        text.erase(0, words.front().size());  // the first line is the text's start, as written
        text.erase(0, text.find_first_not_of(' '));
        indent = "    ";
        continue;
      }
      page.push_back(indent + text.substr(0, cut + at_break->kept));
      text = text.substr(cut + at_break->resume);
      indent = "    ";
    }
    page.push_back(indent + text);
  }
  const float line = px * 1.4f, ph = line * static_cast<float>(page.size() + 1);
  float x0 = (w - pw) / 2, y0 = std::max(0.0f, (h - ph) / 2);
  if (clear_corner > 0 && x0 < clear_corner && y0 < clear_corner) {  // the photodiode's square stays seen
    if (w - pw >= clear_corner + px / 2) x0 = w - pw;
    else y0 = clear_corner + px / 2;
  }
  o.fill_rect(x0, y0, pw, ph, {0.05f, 0.05f, 0.07f, 0.88f});
  o.stroke_rect(x0, y0, pw, ph, 2, {1.0f, 1.0f, 1.0f, 0.5f});
  for (std::size_t i = 0; i < page.size(); ++i)
    o.text(x0 + px, y0 + line * static_cast<float>(i + 1), page[i], {1.0f, 1.0f, 1.0f, i == 0 ? 1.0f : 0.85f});
}

std::vector<std::string> doctor_page_lines(const KioskStage& stage, const render::ProductWindow& win,
                                           const KioskOptions& options, double frame_ms,
                                           const std::string& state_problem) {
  KioskDeviceFacts facts;
  facts.state_problem = state_problem;
  VkPhysicalDeviceProperties props{};
  vkGetPhysicalDeviceProperties(win.ctx->physical_device(), &props);
  facts.vulkan = judge_renderer(win.ctx->device_name(), props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU,
                                win.window->extent().width, win.window->extent().height, frame_ms);
  facts.vulkan.found += " (the kiosk's frames)";
  facts.audio = stage.output ? DoctorCheck{"audio", CheckLevel::ok, stage.audio_status, ""}
                             : DoctorCheck{"audio", CheckLevel::fail, stage.audio_status,
                                           "connect the sound card and check `aplay -l`; `mallet audio devices`"};
  facts.wiimote = wiimote_without_remote(stage.config.input.source);  // as `mallet doctor` says it
  facts.camera = {"camera", CheckLevel::ok, "not used: [input] source = \"" + stage.config.input.source + "\"", ""};
  if (stage.device) {
    const input::wiimote::WiimoteState w = stage.device->state();
    if (w.link == input::wiimote::LinkState::running) {
      facts.connected_remote = remote_identity(w.device);
      facts.wiimote = {"wiimote", CheckLevel::ok, input_line(stage), ""};
    } else
      facts.wiimote = {"wiimote", CheckLevel::fail, input_line(stage), "press 1+2 on the remote; change its batteries"};
  } else if (stage.camera) {
    const IrLink link = ir_link(stage);
    facts.camera = {"camera", CheckLevel::ok, input_line(stage), ""};
    if (link.up) facts.connected_remote = link.identity;
    else facts.camera = {"camera", CheckLevel::fail, input_line(stage), "plug the camera in; `mallet camera list`"};
  }
  DoctorOptions o;
  o.config = options.config;
  o.config_dir = options.config_dir;
  const std::vector<DoctorCheck> checks = run_doctor_with(o, facts);
  std::vector<std::string> lines;
  int failing = 0;
  for (const DoctorCheck& c : checks) {
    // On the page what was found (not the tracker the settings do not use: the page has a
    // line for each of the others, and a 720p screen no more); in the journal every whole
    // line with its fix.
    if (!(c.level == CheckLevel::ok && c.found.rfind("not used", 0) == 0))
      lines.push_back(format_check({c.name, c.level, c.found, ""}));
    journal::notice("doctor: {}", format_check(c).c_str());
    failing += c.level == CheckLevel::fail;
  }
  journal::notice("operator: doctor, {} check(s) failing", failing);
  return lines;
}

}  // namespace mallet::app
