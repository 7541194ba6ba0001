// The portrait layout (core/scene_layout.hpp): the instruments stacked and shown larger on
// a portrait screen, every bar whole in the content, and the contact model over stacked
// rows (core/mallet.hpp): a bar with another below it holds the sphere only through its own
// thickness, so the lower row is played from the space between the rows, and the attract
// mode's ghost goes around the upper row instead of striking it on its way down.
#include "core/scene_layout.hpp"

#include <cmath>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "core/attract_tune.hpp"
#include "core/ghost_player.hpp"
#include "core/mallet.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

using test::percussion;

constexpr double kPortrait = 1080.0 / 1920.0;

//! Screen heights per metre that `scene`'s content is shown at on a screen of `aspect`.
double scale(const Scene& scene, double aspect) {
  const ScreenToWorld f = framed(scene.screen_to_world, aspect);
  return 1.0 / f.height_m();
}

TEST(SceneLayout, APortraitScreenStacksTheInstrumentsAndShowsTheirBarsMoreThanHalfAgainAsWide) {
  const Scene& s = percussion();
  ASSERT_EQ(layout_for(s, kPortrait), SceneLayout::portrait);
  const Scene p = laid_out(s, SceneLayout::portrait);
  EXPECT_EQ(p.layout, SceneLayout::portrait);
  ASSERT_EQ(p.targets.size(), s.targets.size());
  // Each instrument one row below the last, the rows centred on the same x.
  const Instrument& xylo = p.instruments.at(0);
  const Instrument& glock = p.instruments.at(1);
  const Target& x0 = p.targets.at(static_cast<std::size_t>(xylo.targets.front()));
  const Target& g0 = p.targets.at(static_cast<std::size_t>(glock.targets.front()));
  EXPECT_NEAR(x0.top_y - g0.top_y, s.screen_to_world.height_m(), 1e-12);
  const auto middle = [&](const Instrument& inst) {
    return 0.5 * (p.targets.at(static_cast<std::size_t>(inst.targets.front())).x_min +
                  p.targets.at(static_cast<std::size_t>(inst.targets.back())).x_max);
  };
  EXPECT_NEAR(middle(xylo), middle(glock), 1e-12);
  // Every bar is whole in the content, with the same width, note and material.
  for (std::size_t i = 0; i < s.targets.size(); ++i) {
    const Target& a = s.targets[i];
    const Target& b = p.targets[i];
    EXPECT_NEAR(b.x_max - b.x_min, a.x_max - a.x_min, 1e-12);
    EXPECT_EQ(b.note, a.note);
    EXPECT_EQ(b.material, a.material);
    EXPECT_GT(b.x_min - p.mallet_radius_m, p.screen_to_world.left_m) << i;
    EXPECT_LT(b.x_max + p.mallet_radius_m, p.screen_to_world.right_m) << i;
    EXPECT_LT(b.top_y, p.screen_to_world.top_m) << i;
    EXPECT_GT(b.top_y, p.screen_to_world.bottom_m) << i;
  }
  // On 1080 × 1920 a bar is over half as wide again as the landscape layout framed there
  // shows it (the 35 px glockenspiel bars).
  const double px = 1920 * scale(p, kPortrait), px_before = 1920 * scale(s, kPortrait);
  const double glock_bar_m = g0.x_max - g0.x_min;
  EXPECT_GT(glock_bar_m * px, 1.5 * glock_bar_m * px_before);
  EXPECT_GT(glock_bar_m * px, 45.0);
}

TEST(SceneLayout, LandscapeSquareAndUnknownScreensKeepTheLayoutOfTheFile) {
  const Scene& s = percussion();
  for (double aspect : {16.0 / 9, 21.0 / 9, 5.0 / 4, 4.0 / 3, 1.0, 0.0, -1.0, std::nan("")})
    EXPECT_EQ(layout_for(s, aspect), SceneLayout::landscape) << aspect;
  const Scene same = laid_out(s, SceneLayout::landscape);
  EXPECT_EQ(same.layout, SceneLayout::landscape);
  EXPECT_EQ(same.screen_to_world.left_m, s.screen_to_world.left_m);
  EXPECT_EQ(same.targets.at(9).x_min, s.targets.at(9).x_min);
}

TEST(SceneLayout, TheWallAndTheTextureDiscFillMoreOfAPortraitScreen) {
  for (const Scene* s : {&test::wall(), &test::texture()}) {
    ASSERT_EQ(layout_for(*s, kPortrait), SceneLayout::portrait) << s->name;
    const Scene p = portrait_layout(*s);
    EXPECT_GT(scale(p, kPortrait), 1.4 * scale(*s, kPortrait)) << s->name;
    EXPECT_LT(p.screen_to_world.width_m(), s->screen_to_world.width_m()) << s->name;
    EXPECT_EQ(p.screen_to_world.top_m, s->screen_to_world.top_m) << s->name;
    EXPECT_EQ(p.screen_to_world.bottom_m, s->screen_to_world.bottom_m) << s->name;
    for (const Target& t : p.targets) {
      EXPECT_GT(t.x_min, p.screen_to_world.left_m) << s->name;
      EXPECT_LT(t.x_max, p.screen_to_world.right_m) << s->name;
    }
    if (p.texture) {
      const TextureRelief& r = p.texture->relief;
      EXPECT_GT(r.center.x - r.radius_m, p.screen_to_world.left_m);
      EXPECT_LT(r.center.x + r.radius_m, p.screen_to_world.right_m);
    }
  }
}

//! The portrait percussion scene's first xylophone bar (upper row) and the glockenspiel
//! bar under it (lower row).
struct Stacked {
  Scene scene = portrait_layout(percussion());
  const Target& upper() const { return scene.targets.at(static_cast<std::size_t>(scene.instruments[0].targets[3])); }
  //! The bar whose zone is under the upper bar's middle, a row down.
  const Target& lower() const {
    const Target& some = scene.targets.at(static_cast<std::size_t>(scene.instruments[1].targets[0]));
    const std::vector<ContactZone> zones = contact_zones(scene);
    const ContactZone* z = zone_at(zones, {x(), some.top_y + r()});
    if (!z) throw std::runtime_error("no glockenspiel bar under the xylophone's fourth");
    return scene.targets.at(static_cast<std::size_t>(z->target));
  }
  double r() const { return scene.mallet_radius_m; }
  double x() const { return 0.5 * (upper().x_min + upper().x_max); }  //!< over both bars
};

TEST(SceneLayout, APointOverABarOfTheFileIsOverTheSameBarInThePortraitLayout) {
  // `mallet render --layout auto` of a landscape trajectory on a portrait image drew the
  // mallet under the xylophone's rail (issue 48, item 14): a point above each bar, and one
  // beside the instruments, is moved with its instrument; the landscape layout moves nothing.
  const Scene& file = test::percussion();
  const Scene portrait = portrait_layout(file);
  for (const Target& t : file.targets) {
    const Target& laid = portrait.targets.at(static_cast<std::size_t>(t.id));
    const Vec2 above{0.5 * (t.x_min + t.x_max), t.top_y + 0.05};
    const Vec2 moved = to_layout(file, portrait, above);
    EXPECT_NEAR(moved.x, 0.5 * (laid.x_min + laid.x_max), 1e-12) << "bar " << t.id;
    EXPECT_NEAR(moved.y, laid.top_y + 0.05, 1e-12) << "bar " << t.id;
    const Vec2 same = to_layout(file, file, above);
    EXPECT_EQ(same.x, above.x);
    EXPECT_EQ(same.y, above.y);
  }
  // Left of every bar: moved as the leftmost instrument (the xylophone, the upper row).
  const Target& first = file.targets.front();
  const Vec2 beside = to_layout(file, portrait, {first.x_min - 0.3, first.top_y});
  EXPECT_NEAR(beside.y, portrait.targets.front().top_y, 1e-12);
}

TEST(StackedRows, OnlyTheBarsOfTheUpperRowHaveAFloor) {
  for (const ContactZone& z : contact_zones(percussion())) EXPECT_FALSE(std::isfinite(z.floor_y)) << z.target;
  const Stacked st;
  for (const ContactZone& z : contact_zones(st.scene)) {
    const Target& t = st.scene.targets.at(static_cast<std::size_t>(z.target));
    if (t.instrument == "xylophone") EXPECT_DOUBLE_EQ(z.floor_y, t.top_y - t.thickness_m - st.scene.mallet_radius_m);
    else EXPECT_FALSE(std::isfinite(z.floor_y)) << z.target;
  }
}

TEST(StackedRows, TheLowerRowIsStruckFromBetweenTheRowsAndTheSphereIsFreeThere) {
  const Stacked st;
  const Target& lower = st.lower();
  const double r = st.r(), x = st.x();
  Mallet m(st.scene, ContactConfig{});
  // Between the rows: free, not held on the xylophone above.
  const Vec2 between{x, lower.top_y + r + 0.10};
  EXPECT_EQ(m.displayed_centre(between), between);
  ASSERT_FALSE(m.update(0, between));
  EXPECT_TRUE(m.armed());
  const auto hit = m.update(50'000'000, {x, lower.top_y + r - 0.01});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->target, lower.id);
  EXPECT_NEAR(hit->speed_m_per_s, 0.11 / 0.05, 1e-9);
}

TEST(StackedRows, FromBelowTheSphereStopsUnderTheBarAndPopsOnTopPastItsMiddle) {
  const Stacked st;
  const Target& upper = st.upper();
  const double r = st.r(), x = st.x();
  const double top = upper.top_y + r, under = upper.top_y - upper.thickness_m - r;
  Mallet m(st.scene, ContactConfig{});
  EXPECT_EQ(m.displayed_centre({x, under - 0.001}), (Vec2{x, under - 0.001}));  // below: free
  EXPECT_EQ(m.displayed_centre({x, under + 0.001}), (Vec2{x, under}));          // rests under it
  EXPECT_EQ(m.displayed_centre({x, top - 0.001}), (Vec2{x, top}));              // on top
  // Rising into the bar from below is a contact, not a strike; rising clear above re-arms.
  ASSERT_FALSE(m.update(0, {x, under - 0.01}));
  ASSERT_FALSE(m.update(10'000'000, {x, under + 0.005}));
  EXPECT_FALSE(m.armed());
  ASSERT_FALSE(m.update(20'000'000, {x, top + 0.01}));
  EXPECT_TRUE(m.armed());
}

TEST(StackedRows, PushingThroughTheUpperBarStrikesItOnceThenTheLowerBarSounds) {
  const Stacked st;
  const Target& upper = st.upper();
  const Target& lower = st.lower();
  const double r = st.r(), x = st.x();
  Mallet m(st.scene, ContactConfig{});
  std::vector<int> struck;
  // Down at 1 m/s from above the xylophone to below the glockenspiel's plane, 1 kHz.
  const double from = upper.top_y + r + 0.05, to = lower.top_y + r - 0.01;
  for (int k = 0;; ++k) {
    const double y = from - 0.001 * k;
    if (y < to) break;
    if (auto i = m.update(static_cast<Nanos>(k) * 1'000'000, {x, y})) struck.push_back(i->target);
  }
  EXPECT_EQ(struck, (std::vector<int>{upper.id, lower.id}));
}

TEST(StackedRows, TheGhostGoesAroundTheUpperRowAndStrikesEveryNoteOfThePhraseExactlyOnce) {
  const Stacked st;
  const std::vector<ScriptedStrike> s = attract_phrase(st.scene, 500'000'000);
  const GhostPath path = ghost_player(st.scene, s, 1000.0);
  Mallet m(st.scene, ContactConfig{});
  std::vector<int> struck;
  for (const PointerSample& p : path.samples)
    if (auto i = m.update(p.t_ns, {p.x, p.y})) struck.push_back(i->target);
  std::vector<int> wanted;
  for (const ScriptedStrike& k : s) wanted.push_back(k.target);
  EXPECT_EQ(struck, wanted);
  // And it stays on the screen while it goes around.
  const ScreenToWorld view = framed(st.scene.screen_to_world, kPortrait);
  for (const PointerSample& p : path.samples) {
    EXPECT_GE(p.x, view.left_m);
    EXPECT_LE(p.x, view.right_m);
  }
}

}  // namespace
}  // namespace mallet
