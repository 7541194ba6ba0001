#include "app/kiosk/operator_page.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/printf.h>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "app/kiosk/doctor.hpp"
#include "app/kiosk/input_choice.hpp"
#include "core/journal.hpp"
#include "core/visitor_language.hpp"
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
    case GLFW_KEY_PAGE_DOWN: return OperatorAction::next_page;
    case GLFW_KEY_PAGE_UP: return OperatorAction::previous_page;
    default: return OperatorAction::none;
  }
}

namespace {

constexpr float kLargestScale = 0.75f, kSmallestScale = 0.5f, kSmallestTextPx = 12.0f;
constexpr float kLineSpacing = 1.4f;  //!< a row's height, in the text's size
constexpr float kWidestLine = 33.0f;     //!< the panel's widest, in the atlas's size (44 of its largest text) ...
constexpr float kWidestLineEms = 64.0f;  //!< ... or in the text's own size, whichever is wider

//! The mark column's text for a tone (empty: the line has no mark).
const char* mark_of(PageTone tone) {
  switch (tone) {
    case PageTone::warning: return "!";
    case PageTone::fail: return to_string(CheckLevel::fail);
    case PageTone::warn: return to_string(CheckLevel::warn);
    case PageTone::ok: return to_string(CheckLevel::ok);
    default: return "";
  }
}

//! A text's rows: the first fits `first_room`, each continuation `next_room` (in the atlas's
//! pixels). A row ends at a semicolon, a comma, before a parenthesis or between two keys'
//! entries, as far on as fits; else at the last space that fits; a word wider than a row is
//! cut between characters (render::wrap_text), never dropped.
std::vector<std::string> page_rows(const render::FontAtlas& font, std::string text, float first_room,
                                   float next_room) {
  struct Break {
    const char* separator;
    std::size_t kept;    //!< its characters that end the row ("," stays, " (" goes on)
    std::size_t resume;  //!< where the continuation starts, from the separator
  };
  static constexpr Break kBreaks[] = {{"; ", 1, 2}, {", ", 1, 2}, {" (", 0, 1}, {"    ", 0, 4}};
  std::vector<std::string> rows;
  for (;;) {
    const float room = rows.empty() ? first_room : next_room;
    if (font.measure(text) <= room) break;
    std::size_t cut = std::string::npos;
    const Break* at_break = nullptr;
    for (const Break& b : kBreaks)
      for (std::size_t at = text.find(b.separator); at != std::string::npos; at = text.find(b.separator, at + 1))
        if (at > 8 && (cut == std::string::npos || at > cut) && font.measure(text.substr(0, at + b.kept)) <= room)
          cut = at, at_break = &b;
    if (at_break) {
      rows.push_back(text.substr(0, cut + at_break->kept));
      text = text.substr(cut + at_break->resume);
      continue;
    }
    const std::vector<std::string> words = render::wrap_text(font, text, room);  // the words that fit
    if (words.size() < 2) break;
    rows.push_back(words.front());
    text.erase(0, words.front().size());  // the first row is the text's start, as written
    text.erase(0, text.find_first_not_of(' '));
  }
  rows.push_back(text);
  return rows;
}

//! One line's rows, placed relative to the panel's text origin (x from its left, y as a row index).
struct LineRows {
  std::vector<PageRow> rows;  //!< y: the row's index within the line
  int count = 0;              //!< how many rows it takes
};

LineRows line_rows(const render::FontAtlas& font, const PageLine& line, float scale, float room, float mark_w,
                   float head_w) {
  const float em = font.pixel_height() * scale;
  LineRows out;
  float tx = 0;
  if (const std::string mark = mark_of(line.tone); !mark.empty()) {
    out.rows.push_back({0, 0, mark, line.tone});
    tx += mark_w;
  }
  if (!line.head.empty()) {
    out.rows.push_back({tx, 0, line.head, PageTone::status});
    tx += head_w;
  }
  // Continuation rows: under the text's own column beside a mark or a name, else indented.
  const bool hangs = tx > 0;
  const float next_x = hangs ? tx : tx + 1.5f * em;
  const PageTone text_tone =
      line.tone == PageTone::title || line.tone == PageTone::warning || line.tone == PageTone::keys ? line.tone
                                                                                                      : PageTone::status;
  int row = 0;
  std::size_t from = 0;
  for (;;) {  // '\n' starts a continuation row
    const std::size_t nl = line.text.find('\n', from);
    const std::string part = line.text.substr(from, nl == std::string::npos ? std::string::npos : nl - from);
    const float first_x = row == 0 ? tx : next_x;
    for (std::string& r : page_rows(font, part, (room - first_x) / scale, (room - next_x) / scale)) {
      out.rows.push_back({row == 0 ? tx : next_x, static_cast<float>(row), std::move(r), text_tone});
      ++row;
    }
    if (nl == std::string::npos) break;
    from = nl + 1;
  }
  out.count = std::max(row, 1);
  return out;
}

}  // namespace

namespace {

//! Moves a laid-out page by (dx, dy).
PageLayout moved(PageLayout layout, float dx, float dy) {
  layout.x += dx;
  layout.y += dy;
  for (PageRow& r : layout.rows) r.x += dx, r.y += dy;
  return layout;
}

}  // namespace

PageLayout layout_operator_page(const render::FontAtlas& font, const std::vector<PageLine>& lines, float w, float h,
                                float clear_corner, int page) {
  if (clear_corner > 0) {  // the photodiode's square stays seen: the page moved right, else laid out below it
    const PageLayout plain = layout_operator_page(font, lines, w, h, 0, page);
    if (plain.x >= clear_corner || plain.y >= clear_corner) return plain;
    const float gap = font.pixel_height() * plain.scale / 2;
    if (w - plain.width >= clear_corner + gap) return moved(plain, w - plain.width - plain.x, 0);
    const float top = std::ceil(clear_corner + gap);  // whole pixels: the baselines stay crisp
    return moved(layout_operator_page(font, lines, w, h - top, 0, page), 0, top);
  }
  const float px = font.pixel_height();
  const float smallest = std::clamp(kSmallestTextPx / px, kSmallestScale, kLargestScale);
  PageLayout out;
  std::vector<LineRows> laid;
  int max_rows = 0;
  float room = 0;
  for (float scale = kLargestScale;; scale = std::max(smallest, scale - 0.05f)) {
    const float em = px * scale;
    out.scale = scale;
    // As wide as the largest text's panel whatever the text's size (smaller text then wraps
    // less, rather than in a narrower panel: a long language used half of a wide screen and
    // took two pages where English took one), and never wider than the screen.
    out.width = std::min(w - 2 * em, std::max(kWidestLine * px, kWidestLineEms * px * kLargestScale));
    room = out.width - 2 * em;
    float mark_w = 0, head_w = 0;
    for (const PageLine& l : lines) {
      if (*mark_of(l.tone)) mark_w = std::max(mark_w, font.measure(mark_of(l.tone)) * scale + 0.6f * em);
      if (!l.head.empty()) head_w = std::max(head_w, font.measure(l.head) * scale + em);
    }
    laid.clear();
    int total = 0;
    for (const PageLine& l : lines) {
      laid.push_back(line_rows(font, l, scale, room, mark_w, head_w));
      total += laid.back().count;
    }
    max_rows = static_cast<int>(std::floor((h - em) / (kLineSpacing * em))) - 1;  // a row's room above and below
    if (total <= max_rows || scale <= smallest) break;
  }
  // The lines on screens taken in turn when they do not fit one: the title and the keys'
  // line on each (the way back is on every screen, not only the last), then as many whole
  // lines as fit with the footer's row (a line taller than a screen has one alone).
  std::vector<std::vector<std::size_t>> screens(1);
  const bool titled = !lines.empty() && lines.front().tone == PageTone::title;
  std::vector<std::size_t> keys;  // on every screen, after its lines
  int pinned = titled ? laid.front().count : 0;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i].tone == PageTone::keys) keys.push_back(i), pinned += laid[i].count;
  const auto paged = [&](std::size_t i) { return !(titled && i == 0) && lines[i].tone != PageTone::keys; };
  int total = pinned;
  for (std::size_t i = 0; i < laid.size(); ++i)
    if (paged(i)) total += laid[i].count;
  const int room_rows = total <= max_rows ? max_rows : max_rows - 1;  // the footer's row
  int used = pinned;
  for (std::size_t i = 0; i < laid.size(); ++i) {
    if (!paged(i)) continue;
    if (used + laid[i].count > room_rows && !screens.back().empty()) {
      screens.emplace_back();
      used = pinned;
    }
    screens.back().push_back(i);
    used += laid[i].count;
  }
  out.pages = static_cast<int>(screens.size());
  out.page = ((page % out.pages) + out.pages) % out.pages;
  std::vector<std::size_t> shown = screens[static_cast<std::size_t>(out.page)];
  if (titled) shown.insert(shown.begin(), 0);
  shown.insert(shown.end(), keys.begin(), keys.end());

  const float em = px * out.scale, line = kLineSpacing * em;
  int rows = 0;
  for (std::size_t i : shown) rows += laid[i].count;
  if (out.pages > 1) ++rows;
  out.height = line * static_cast<float>(rows + 1);
  out.x = (w - out.width) / 2;
  out.y = std::max(0.0f, (h - out.height) / 2);
  // Whole-pixel baselines keep the glyphs crisp.
  int row = 0;
  for (std::size_t i : shown) {
    for (const PageRow& r : laid[i].rows)
      out.rows.push_back({out.x + em + r.x, std::round(out.y + line * (static_cast<float>(row + 1) + r.y)), r.text,
                          r.tone});
    row += laid[i].count;
  }
  if (out.pages > 1)
    out.rows.push_back({out.x + em, std::round(out.y + line * static_cast<float>(row + 1)),
                        // Page Down wraps: from the last screen it goes back to the first.
                        fmt::sprintf(out.page + 1 < out.pages ? tr("Page Down: more   (%d of %d)")
                                                              : tr("Page Down: back to the first   (%d of %d)"),
                                     out.page + 1, out.pages),
                        PageTone::title});
  return out;
}

void draw_operator_page(render::Overlay& o, const PageLayout& layout) {
  o.fill_rect(layout.x, layout.y, layout.width, layout.height, {0.05f, 0.05f, 0.07f, 0.88f});
  o.stroke_rect(layout.x, layout.y, layout.width, layout.height, 2, {1.0f, 1.0f, 1.0f, 0.5f});
  // A right-to-left language reads the page from its right edge: a row with its letters
  // aligned right, its columns mirrored. A row of Latin text (a path, a key, a figure, a
  // check's name and mark) is laid out by its own direction, from the left edge, so that the
  // status lines stay straight columns to scan, not ragged on the right.
  const bool rtl = render::right_to_left(visitor_language());
  for (const PageRow& r : layout.rows) {
    std::array<float, 4> color{1.0f, 1.0f, 1.0f, 0.85f};
    switch (r.tone) {
      case PageTone::title: color = {1.0f, 1.0f, 1.0f, 1.0f}; break;
      case PageTone::status:
      case PageTone::keys: break;
      case PageTone::warning:
      case PageTone::warn: color = {1.0f, 0.76f, 0.28f, 1.0f}; break;
      case PageTone::fail: color = {1.0f, 0.45f, 0.42f, 1.0f}; break;
      case PageTone::ok: color = {0.45f, 0.86f, 0.5f, 1.0f}; break;
    }
    if (rtl && o.atlas().shape(r.text).right_to_left)
      o.text(layout.x + layout.width - (r.x - layout.x), r.y, r.text, color, render::TextAlign::right, layout.scale);
    else
      o.text(r.x, r.y, r.text, color, render::TextAlign::left, layout.scale);
  }
}

std::vector<PageLine> doctor_page_lines(const KioskStage& stage, const render::ProductWindow& win,
                                           const KioskOptions& options, double frame_ms,
                                           const std::string& state_problem) {
  KioskDeviceFacts facts;
  facts.state_problem = state_problem;
  facts.shown_language = visitor_language();  // the operator's L, not the settings' language
  VkPhysicalDeviceProperties props{};
  vkGetPhysicalDeviceProperties(win.ctx->physical_device(), &props);
  facts.vulkan = judge_renderer(win.ctx->device_name(), props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU,
                                win.window->extent().width, win.window->extent().height, frame_ms);
  facts.vulkan.found += " (the kiosk's frames that drew)";
  // Why the output did not open, as the command says it (the status line's own prefix aside).
  const std::string silent = "audio: none (running silent): ";
  facts.audio = stage.output ? judge_audio_output(stage.config, *stage.output)
                             : audio_missing(stage.audio_status.rfind(silent, 0) == 0
                                                 ? stage.audio_status.substr(silent.size())
                                                 : stage.audio_status);
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
  std::vector<PageLine> lines;
  int failing = 0;
  for (const DoctorCheck& c : checks) {
    // On the page every check `mallet doctor` prints, in its words (the tracker the settings
    // do not use too: "not used"), with the fix of one that is not ok; in the journal each whole.
    {
      const PageTone tone = c.level == CheckLevel::fail   ? PageTone::fail
                            : c.level == CheckLevel::warn ? PageTone::warn
                                                          : PageTone::ok;
      std::string text = c.found;
      std::replace(text.begin(), text.end(), '\n', ' ');
      if (!c.fix.empty()) text += "\nfix: " + c.fix;
      lines.push_back({tone, text, c.name});
    }
    journal::notice("doctor: {}", format_check(c).c_str());
    failing += c.level == CheckLevel::fail;
  }
  journal::notice("operator: doctor, {} check(s) failing", failing);
  return lines;
}

}  // namespace mallet::app
