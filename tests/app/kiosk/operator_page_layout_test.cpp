// The operator page laid out for the screen (issue 29, items 1 and 2): at every shape, with
// the walkthrough's three faults or with many, every row stays on the screen and inside the
// panel, no word is lost, the warnings come first, and a doctor's check keeps its columns.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/printf.h>

#include "app/kiosk/operator_page.hpp"
#include "core/visitor_catalogues.hpp"
#include "core/visitor_language.hpp"
#include "golden_match.hpp"
#include "render/render_setup.hpp"
#include "test_paths.hpp"
#include "text_box_check.hpp"

namespace mallet::app {
namespace {

struct Shape {
  float w, h;
};
constexpr Shape kShapes[] = {{1920, 1080}, {1280, 1024}, {1080, 1920}, {2560, 1080}, {1280, 720}, {800, 600}};

// The page a running kiosk showed in the walkthrough, with its three faults.
std::vector<PageLine> walkthrough_page() {
  return {
      {PageTone::title, "Mallet: operator page   quality: balanced   language: en"},
      {PageTone::warning,
       "drop-in /etc/mallet/mallet.d/50-room.toml skipped: /etc/mallet/mallet.d/50-room.toml:3:1: [audio] "
       "volum: unknown key (known: volume, device, output_latency_ms, soundfont)"},
      {PageTone::warning,
       "scene choice /etc/mallet/scenes/bumps.toml skipped: /etc/mallet/scenes/bumps.toml:12:12: [[bumps]] "
       "radius_m: must be > 0, got -0.08"},
      {PageTone::warning,
       "visitor study off: /etc/mallet/mallet.toml: [study] visitor_protocol: "
       "/etc/mallet/study/visitor.toml: cannot open the file (No such file or directory)"},
      {PageTone::status, "input: mouse (no Wii Remote found at start-up); mouse: the window system's events, "
                         "once a frame (evdev: no mouse among /dev/input/event*)"},
      {PageTone::status, "audio: none (running silent)"},
      {PageTone::status, "frame: 16.6 ms (its work 12.5 ms)   uptime: 0 h 00 min"},
      {PageTone::status, "volume 80 %  (Up / Down)"},
      {PageTone::status, "actuator gain 0.20  (Left / Right)"},
      {PageTone::status, "R recalibrate    T latency test    D doctor    L language    Q quit    Esc close"},
      {PageTone::status, "scene: percussion.toml  (S next)"},
      {PageTone::status, "calibration: R runs the screen with the mouse (not saved)"},
      {PageTone::status, "timing: align asap, prediction 10 ms ahead, frames immediate, frame period 16.5 ms "
                         "(60.6 Hz), display 0 ms, audio out 0.0 ms (the device's)"},
      {PageTone::status, "settings: /work/main/config/mallet.toml"},
  };
}

std::vector<PageLine> doctor_page() {
  return {
      {PageTone::title, "Mallet: operator page   quality: balanced   language: en"},
      {PageTone::ok, "lavapipe (LLVM 15.0.6, 256 bits), a CPU renderer, 1280x1024 at 12.5 ms a frame", "vulkan"},
      {PageTone::fail, "none (running silent)\nfix: connect the sound card and check `aplay -l`; `mallet audio devices`",
       "audio"},
      {PageTone::warn,
       "no Wii Remote found among the HID devices (the mouse is used)\nfix: pair the remote (press 1+2) and "
       "see docs/operators.md, \"Pairing a Wii Remote\"",
       "wiimote"},
      {PageTone::ok, "/var/lib/mallet writable", "state"},
      {PageTone::status, "D back to the page    Esc close"},
  };
}

std::vector<std::string> words_of(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

// Every row inside the screen and the panel: its ink from the ascent to the descent, its
// width as the font sets it at the layout's scale.
void expect_on_screen(const render::FontAtlas& font, const PageLayout& page, Shape s, const std::string& what) {
  EXPECT_GE(page.x, 0) << what;
  EXPECT_GE(page.y, 0) << what;
  EXPECT_LE(page.x + page.width, s.w + 0.5f) << what;
  EXPECT_LE(page.y + page.height, s.h + 0.5f) << what;
  EXPECT_GE(font.pixel_height() * page.scale, 12.0f - 1e-3f) << what << ": the text stays readable";
  for (const PageRow& r : page.rows) {
    const float right = r.x + font.measure(r.text) * page.scale;
    EXPECT_GE(r.x, page.x) << what << ": " << r.text;
    EXPECT_LE(right, page.x + page.width) << what << ": " << r.text;
    EXPECT_GE(r.y - font.ascent() * page.scale, page.y) << what << ": " << r.text;
    EXPECT_LE(r.y + font.descent() * page.scale, page.y + page.height) << what << ": " << r.text;
  }
}

// The words of every line, in order, across all of the page's screens; the title once a screen.
void expect_every_word(const render::FontAtlas& font, const std::vector<PageLine>& lines, Shape s,
                       const std::string& what) {
  std::vector<std::string> want;
  for (std::size_t i = 1; i < lines.size(); ++i) {  // the title is checked on each screen
    if (lines[i].tone == PageTone::keys) continue;  // and so is the keys' line
    for (const char* mark : {"!", "fail", "warn", "ok"})
      if ((lines[i].tone == PageTone::warning && std::string(mark) == "!") ||
          (lines[i].tone == PageTone::fail && std::string(mark) == "fail") ||
          (lines[i].tone == PageTone::warn && std::string(mark) == "warn") ||
          (lines[i].tone == PageTone::ok && std::string(mark) == "ok"))
        want.emplace_back(mark);
    for (const std::string& w : words_of(lines[i].head)) want.push_back(w);
    for (const std::string& w : words_of(lines[i].text)) want.push_back(w);
  }
  const PageLayout first = layout_operator_page(font, lines, s.w, s.h, 0, 0);
  std::vector<std::string> got;
  for (int p = 0; p < first.pages; ++p) {
    const PageLayout page = layout_operator_page(font, lines, s.w, s.h, 0, p);
    ASSERT_EQ(page.page, p);
    ASSERT_EQ(page.pages, first.pages);
    expect_on_screen(font, page, s, what + ", screen " + std::to_string(p + 1));
    ASSERT_FALSE(page.rows.empty());
    EXPECT_EQ(page.rows.front().text, lines.front().text) << what << ": the title heads each screen";
    const std::size_t footer = page.pages > 1 ? 1 : 0;
    for (std::size_t r = 1; r + footer < page.rows.size(); ++r)
      if (page.rows[r].tone != PageTone::keys)
        for (const std::string& w : words_of(page.rows[r].text)) got.push_back(w);
  }
  EXPECT_EQ(got, want) << what << ": " << first.pages << " screen(s)";
}

TEST(OperatorPageLayout, TheWalkthroughsThreeFaultsFitEveryShapeWithEveryWordAndWarningsFirst) {
  for (const Shape s : kShapes) {
    const auto font = render::overlay_font({static_cast<std::uint32_t>(s.w), static_cast<std::uint32_t>(s.h)});
    const std::string what = std::to_string(int(s.w)) + "x" + std::to_string(int(s.h));
    const std::vector<PageLine> lines = walkthrough_page();
    const PageLayout page = layout_operator_page(*font, lines, s.w, s.h);
    EXPECT_EQ(page.pages, 1) << what << ": fourteen lines fit one screen";
    expect_every_word(*font, lines, s, what);
    // The warnings' marks come right after the title's row, before any status row.
    std::vector<float> warning_ys, status_ys;
    for (const PageRow& r : page.rows)
      (r.tone == PageTone::warning ? warning_ys : status_ys).push_back(r.y);
    ASSERT_EQ(std::count_if(page.rows.begin(), page.rows.end(), [](const PageRow& r) { return r.text == "!"; }), 3)
        << what;
    for (float wy : warning_ys)
      for (std::size_t i = 1; i < status_ys.size(); ++i) EXPECT_LT(wy, status_ys[i]) << what;
  }
}

TEST(OperatorPageLayout, ManyWarningsTakeScreensInTurnAndLoseNoWord) {
  std::vector<PageLine> lines = walkthrough_page();
  for (int i = 0; i < 40; ++i)
    lines.insert(lines.begin() + 1, PageLine(PageTone::warning, "drop-in /etc/mallet/mallet.d/" + std::to_string(i) +
                                                                    "-x.toml skipped: a long reason, with words, "
                                                                    "that wraps onto a second row on most screens"));
  for (const Shape s : kShapes) {
    const auto font = render::overlay_font({static_cast<std::uint32_t>(s.w), static_cast<std::uint32_t>(s.h)});
    const std::string what = std::to_string(int(s.w)) + "x" + std::to_string(int(s.h));
    EXPECT_GT(layout_operator_page(*font, lines, s.w, s.h).pages, 1) << what;
    expect_every_word(*font, lines, s, what);
    // Page Up from the first screen is the last; Page Down from the last, the first.
    const PageLayout first = layout_operator_page(*font, lines, s.w, s.h, 0, 0);
    EXPECT_EQ(layout_operator_page(*font, lines, s.w, s.h, 0, -1).page, first.pages - 1);
    EXPECT_EQ(layout_operator_page(*font, lines, s.w, s.h, 0, first.pages).page, 0);
    // The footer says what Page Down does: more, except on the last screen, where it goes back.
    EXPECT_EQ(first.rows.back().text, "Page Down: more   (1 of " + std::to_string(first.pages) + ")") << what;
    const PageLayout last = layout_operator_page(*font, lines, s.w, s.h, 0, first.pages - 1);
    const std::string n = std::to_string(first.pages);
    EXPECT_EQ(last.rows.back().text, "Page Down: back to the first   (" + n + " of " + n + ")") << what;
  }
}

TEST(OperatorPageLayout, NoTextOfThePageOrOfAnyDoctorScreenIsDrawnOverAnotherOrOffTheScreen) {
  // The overlap contract (issue 48, item 4) on the operator page and on each screen of the
  // doctor's view, as drawn (the overlay's record of every text's ink), at every shape, in
  // every shipped language (right-to-left rows mirrored, Latin rows from the left).
  int screens = 0;
  for (const Shape s : kShapes) {
    const auto font = render::overlay_font({static_cast<std::uint32_t>(s.w), static_cast<std::uint32_t>(s.h)});
    for (const std::string& language : visitor_languages()) {
      std::vector<std::string> problems;
      start_visitor_language(language, problems);
      ASSERT_TRUE(problems.empty()) << problems.front();
      for (const std::vector<PageLine>& lines : {walkthrough_page(), doctor_page()}) {
        const int pages = layout_operator_page(*font, lines, s.w, s.h).pages;
        for (int p = 0; p < pages; ++p) {
          render::Overlay overlay(*font);
          draw_operator_page(overlay, layout_operator_page(*font, lines, s.w, s.h, 0, p));
          ASSERT_FALSE(overlay.text_boxes().empty());
          for (const std::string& problem : test::text_box_problems(overlay, s.w, s.h))
            ADD_FAILURE() << language << " " << s.w << "x" << s.h << " screen " << p + 1 << ": " << problem;
          ++screens;
        }
      }
    }
  }
  use_visitor_language("en");
  std::printf("%d page screens, each text against every other\n", screens);
}

TEST(OperatorPageLayout, TheKeysLineIsOnEveryScreenOfAPageThatTakesSeveral) {
  // The doctor's view on two screens had "D back to the page    Esc close" on its last one
  // only (issue 48, item 13): the keys' line stands on each, above the footer, once.
  std::vector<PageLine> lines = walkthrough_page();
  for (int i = 0; i < 40; ++i)
    lines.insert(lines.begin() + 1, PageLine(PageTone::warning, "a warning " + std::to_string(i) + " that takes a row"));
  lines.insert(lines.begin() + 3, PageLine(PageTone::keys, "D back to the page    Esc close"));
  for (const Shape s : kShapes) {
    const auto font = render::overlay_font({static_cast<std::uint32_t>(s.w), static_cast<std::uint32_t>(s.h)});
    const std::string what = std::to_string(int(s.w)) + "x" + std::to_string(int(s.h));
    const int pages = layout_operator_page(*font, lines, s.w, s.h).pages;
    ASSERT_GT(pages, 1) << what;
    for (int p = 0; p < pages; ++p) {
      const PageLayout screen = layout_operator_page(*font, lines, s.w, s.h, 0, p);
      ASSERT_GE(screen.rows.size(), 2u);
      EXPECT_EQ(std::count_if(screen.rows.begin(), screen.rows.end(),
                              [](const PageRow& r) { return r.text == "D back to the page    Esc close"; }),
                1)
          << what << " screen " << p + 1;
      EXPECT_EQ(screen.rows[screen.rows.size() - 2].text, "D back to the page    Esc close") << what;
    }
    expect_every_word(*font, lines, s, what);
  }
}

TEST(OperatorPageLayout, TheDoctorsChecksKeepTheirColumnsAndShowEachFixWhole) {
  for (const Shape s : kShapes) {
    const auto font = render::overlay_font({static_cast<std::uint32_t>(s.w), static_cast<std::uint32_t>(s.h)});
    const std::string what = std::to_string(int(s.w)) + "x" + std::to_string(int(s.h));
    const std::vector<PageLine> lines = doctor_page();
    expect_every_word(*font, lines, s, what);
    const PageLayout page = layout_operator_page(*font, lines, s.w, s.h);
    // Each level at one x, each name at one x right of every level, each finding at one x
    // right of every name; a fix's row under its finding.
    std::map<std::string, float> level_x, name_x, text_x;
    for (std::size_t i = 0; i + 2 < page.rows.size(); ++i) {
      const PageRow& r = page.rows[i];
      if (r.text == "fail" || r.text == "warn" || r.text == "ok") {
        level_x[r.text] = r.x;
        name_x[page.rows[i + 1].text] = page.rows[i + 1].x;
        text_x[page.rows[i + 1].text] = page.rows[i + 2].x;
        EXPECT_EQ(page.rows[i + 1].y, r.y) << what;
        EXPECT_EQ(page.rows[i + 2].y, r.y) << what;
      }
    }
    ASSERT_EQ(level_x.size(), 3u) << what;
    ASSERT_EQ(name_x.size(), 4u) << what;
    for (const auto& [name, x] : name_x) {
      EXPECT_EQ(x, name_x.begin()->second) << what << ": " << name;
      EXPECT_EQ(text_x[name], text_x.begin()->second) << what << ": " << name;
      for (const auto& [level, lx] : level_x) EXPECT_LT(lx + font->measure(level) * page.scale, x) << what;
      EXPECT_LT(x + font->measure(name) * page.scale, text_x[name]) << what;
    }
    for (const auto& [level, x] : level_x) EXPECT_EQ(x, level_x.begin()->second) << what << ": " << level;
    // The fix starts a row of its own, in the finding's column.
    const auto fix = std::find_if(page.rows.begin(), page.rows.end(),
                                  [](const PageRow& r) { return r.text.rfind("fix: connect", 0) == 0; });
    ASSERT_NE(fix, page.rows.end()) << what;
    EXPECT_EQ(fix->x, text_x.begin()->second) << what;
    EXPECT_EQ(std::count_if(page.rows.begin(), page.rows.end(),
                            [](const PageRow& r) { return r.text.find("...") != std::string::npos; }),
              0)
        << what << ": nothing is cut";
  }
}

//! The percussion scene drawn as the goldens are (lavapipe, validation on; another device by
//! $MALLET_GOLDEN_DEVICE).
render::HeadlessOptions golden_options(std::uint32_t w, std::uint32_t h) {
  render::HeadlessOptions o;
  o.size = {w, h};
  o.validation = render::Validation::required;
  o.cache_dir = "";
  o.device = "llvmpipe";
  if (const char* d = std::getenv("MALLET_GOLDEN_DEVICE")) o.device = d;
  return o;
}

// The page with the walkthrough's three faults over the percussion scene, at 16:9 and 5:4,
// as lavapipe draws it (tests/golden_match.hpp; MALLET_UPDATE_GOLDENS=1 to update).
TEST(OperatorPageGolden, WithThreeWarningsAt16x9And5x4) {
  for (const auto& [w, h, name] : {std::tuple{960u, 540u, "operator_page_warnings_16x9"},
                                   std::tuple{640u, 512u, "operator_page_warnings_5x4"}}) {
    const render::HeadlessOptions o = golden_options(w, h);
    render::HeadlessRenderer r(test::percussion(), o);
    const auto font = render::overlay_font(o.size);
    render::Overlay overlay(*font);
    const PageLayout page = layout_operator_page(*font, walkthrough_page(), static_cast<float>(w),
                                                 static_cast<float>(h));
    ASSERT_EQ(page.pages, 1) << name;
    draw_operator_page(overlay, page);
    render::FrameState state;
    state.draw_mallet = false;
    state.overlay = &overlay;
    test::expect_matches_golden(r.render(state), name, r);
  }
}

// The page in Arabic (right to left: each row of Arabic aligned right; a row of English, a
// file's problem as the kiosk shows one, laid out by its own direction from the left edge,
// not ragged on the right: issue 48, item 10) and Hindi (Devanagari's conjuncts), its texts
// from the built catalogues.
TEST(OperatorPageGolden, InArabicAndHindi) {
  for (const std::string language : {"ar", "hi"}) {
    std::vector<std::string> problems;
    start_visitor_language(language, problems);
    ASSERT_TRUE(problems.empty()) << problems.front();
    const std::vector<PageLine> lines{
        {PageTone::title, fmt::sprintf(tr("Mallet: operator page   quality: %s   language: %s"), "balanced", language)},
        {PageTone::warning, "drop-in /etc/mallet/mallet.d/50-room.toml skipped: /etc/mallet/mallet.d/50-room.toml:3:1: "
                            "[audio] volum: unknown key"},
        {PageTone::status, tr("Mouse")},
        {PageTone::status, fmt::sprintf(tr("volume %.0f %%  (Up / Down)"), 80.0)},
        {PageTone::status, fmt::sprintf(tr("actuator gain %.2f  (Left / Right)"), 0.2)},
        {PageTone::status, tr("R recalibrate    T latency test    D doctor    L language    Q quit    Esc close")},
        {PageTone::status, fmt::sprintf(tr("scene: %s  (S next)"), "percussion.toml")},
        {PageTone::status, tr("calibration: R runs the screen with the mouse (not saved)")},
    };
    const render::HeadlessOptions o = golden_options(960, 540);
    render::HeadlessRenderer r(test::percussion(), o);
    const auto font = render::overlay_font(o.size);
    render::Overlay overlay(*font);
    const PageLayout page = layout_operator_page(*font, lines, 960.0f, 540.0f);
    ASSERT_EQ(page.pages, 1) << language;
    draw_operator_page(overlay, page);
    if (language == "ar") {  // every row ends a letter's width in from the panel's right edge
      float right = 0;
      for (const render::OverlayVertex& v : overlay.vertices())
        if (v.u != font->solid_u() || v.v != font->solid_v()) right = std::max(right, v.x);
      EXPECT_NEAR(right, page.x + page.width - font->pixel_height() * page.scale, font->pixel_height() * 0.5f);
      int english = 0;
      for (const render::TextBox& b : overlay.text_boxes())
        if (b.text.find("/etc/mallet") != std::string::npos) {
          ++english;
          EXPECT_LT(b.x0, page.x + page.width / 3) << "an English row reads from the left: " << b.text;
        }
      EXPECT_GE(english, 1);
    }
    use_visitor_language("en");
    render::FrameState state;
    state.draw_mallet = false;
    state.overlay = &overlay;
    test::expect_matches_golden(r.render(state), "operator_page_" + language, r);
  }
}

TEST(OperatorPageLayout, TheLatencySquaresCornerStaysClearAndThePageStaysOnTheScreen) {
  // The square (4 letters a side) during the ten pulses: the page beside it where the screen
  // is wide enough, else below it, laid out again in the height left (a portrait screen, the
  // doctor's many lines).
  for (const Shape s : kShapes) {
    const auto font = render::overlay_font({static_cast<std::uint32_t>(s.w), static_cast<std::uint32_t>(s.h)});
    const float side = font->pixel_height() * 4;
    for (const std::vector<PageLine>& lines : {walkthrough_page(), doctor_page()}) {
      const PageLayout page = layout_operator_page(*font, lines, s.w, s.h, side);
      const std::string what = std::to_string(int(s.w)) + "x" + std::to_string(int(s.h));
      EXPECT_TRUE(page.x >= side || page.y >= side) << what << ": " << page.x << ", " << page.y;
      expect_on_screen(*font, page, s, what + " beside the square");
      for (const PageRow& r : page.rows) EXPECT_EQ(r.y, std::round(r.y)) << what << ": whole-pixel baselines";
    }
  }
}

}  // namespace
}  // namespace mallet::app
