#pragma once
// The contact solver: the mallet head is a sphere of radius r whose centre follows the
// hand in the vertical plane. Between two pointer samples the hand moves on a straight
// line; the solver sweeps that segment against the bars' top faces, finds the exact
// fractional contact time and the normal impact speed, and emits one Impact per strike.
//
// Contact model (documented in docs/researchers.md, "How a strike is detected"):
//  * Each bar has a contact zone: its top face widened by r on both sides (the sphere's
//    edge touching the bar's corner counts), cut at the middle of the gap where two
//    zones of the same height would overlap. A point on that cut belongs to the bar on
//    the right. Every x inside an instrument therefore names exactly one bar; a gap
//    wider than 2r (e.g. between the two instruments) lets the mallet pass.
//  * A strike happens when the segment crosses the zone's contact plane (top + r)
//    downwards while armed. Its time is where the segment meets the plane; its speed is
//    the segment's downward speed (exact for straight-line motion), clamped to
//    `max_impact_speed_m_per_s`. A crossing slower than `min_impact_speed_m_per_s` is a
//    touch: it disarms but makes no sound.
//  * The displayed sphere never goes below a contact plane: while the hand is below it,
//    the sphere rests on the surface ("stopping the cursor at the collision point").
//  * After a strike (or any contact) the solver re-arms only when the hand rises
//    `rearm_height_m` above the plane it touched: jitter around a surface makes no
//    second strike, and sliding along the bars is not a strike.
//  * Entering a zone sideways below its plane (from a gap, or past an instrument's end)
//    is a contact without a strike: nothing crossed the top face.
//  * Samples with a non-finite position, or a time not after the previous sample's,
//    are ignored and counted (see Counters).
//  * Instruments stacked one above the other (a portrait screen, core/scene_layout.hpp):
//    a bar higher than another of the scene's bars holds the sphere only through its own
//    thickness. Below its underside (the centre lower than the floor, bottom − r) the
//    sphere is under the bar, free, over the instrument below; inside the bar it rests on
//    the nearer face (the top, or the underside from below). Passing under the bar re-arms,
//    as rising clear of it does. Where every bar is at one height (the scenes side by side),
//    a bar holds the sphere however low the hand goes, as above.
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "core/geometry.hpp"
#include "core/impact.hpp"
#include "core/pointer_sample.hpp"
#include "core/scene.hpp"

namespace mallet {

struct ContactConfig {
  double rearm_height_m = 0.003;          //!< hysteresis above the contact plane
  double min_impact_speed_m_per_s = 0.005;
  double max_impact_speed_m_per_s = 10.0; //!< faster strikes are clamped (and counted)
};

//! A bar's contact zone in terms of the sphere's centre.
struct ContactZone {
  int target = -1;
  double lo = 0, hi = 0;   //!< centre x range; `hi` excluded when `hi_open`
  bool hi_open = false;
  double plane_y = 0;      //!< centre height at contact: top_y + r
  //! The centre's height touching the bar's underside (bottom − r) when another bar of the
  //! scene is lower; −∞ (holds at any depth) otherwise.
  double floor_y = -std::numeric_limits<double>::infinity();

  bool contains(double x) const { return x >= lo && (hi_open ? x < hi : x <= hi); }
  //! The centre at `c` is on or in this bar: inside its zone, below its plane, not under it.
  bool holds(Vec2 c) const { return contains(c.x) && c.y <= plane_y && c.y >= floor_y; }
  //! Where the sphere rests for a centre it holds: on the top, or under the underside when
  //! the centre is in the lower half of the bar (reached from below).
  double rest_y(double y) const { return std::isfinite(floor_y) && y < 0.5 * (plane_y + floor_y) ? floor_y : plane_y; }
};

//! The zone that a sphere centred at `c` is over or on: of the zones containing c.x whose
//! floor is not above c.y, the highest; nullptr if none.
const ContactZone* zone_at(const std::vector<ContactZone>& zones, Vec2 c);

class Mallet {
 public:
  struct Counters : SampleCounters {
    std::uint64_t impacts = 0;
    std::uint64_t touches_below_min_speed = 0;
    std::uint64_t clamped_speed = 0;
  };

  Mallet(const Scene& scene, ContactConfig config);

  //! Feeds the hand (the sphere centre, world metres) at time t. Returns the strike that
  //! happened in the segment from the previous accepted sample to this one, if any.
  std::optional<Impact> update(Nanos t_ns, Vec2 hand);

  //! Where the sphere is drawn for a hand position: held on the surface while the hand
  //! is below a contact plane, free otherwise. A pure function of the hand.
  Vec2 displayed_centre(Vec2 hand) const;

  //! The zone a centre is over or on (the free function zone_at).
  const ContactZone* zone_at(Vec2 c) const { return mallet::zone_at(zones_, c); }

  const std::vector<ContactZone>& zones() const { return zones_; }
  const Counters& counters() const { return counters_; }
  bool armed() const { return armed_; }
  void reset();  //!< forget the previous sample (e.g. tracking was lost)

  //! Treats `zone` as struck now, with the hand at height `hand_y`: a strike decided
  //! from a prediction (core/strike_detector.hpp) must not sound again when the real
  //! crossing follows. Re-arms only when the hand rises `rearm_height_m` above
  //! max(hand_y, zone.plane_y), so a hand that stops just above the bar after a wrong
  //! prediction makes no second note while it hovers there. A real contact that follows
  //! moves the re-arm height down to the plane's, as after any strike.
  void disarm(const ContactZone& zone, double hand_y);

  //! The strike on `zone`'s bar at t, with its current material and note: what update()
  //! emits, and what a predicted strike carries (speed already clamped by the caller).
  Impact impact_on(const ContactZone& zone, Nanos t_ns, double speed_m_per_s, double x_m) const;

  //! The material a target's strikes carry from now on (the wall's material switch);
  //! ignored unless both indices are valid. Initially each target's configured material.
  void set_material(int target, int material);
  int material_of(int target) const;

 private:
  struct Last {
    Nanos t_ns;
    Vec2 hand;
  };

  const Scene* scene_;
  ContactConfig config_;
  std::vector<ContactZone> zones_;
  std::vector<int> materials_;  //!< per target
  std::optional<Last> last_;
  bool armed_ = true;
  double rearm_y_ = 0;
  double rearm_floor_y_ = -std::numeric_limits<double>::infinity();  //!< passing under re-arms
  Counters counters_;
};

//! Builds the contact zones of a scene for a sphere of the scene's radius.
std::vector<ContactZone> contact_zones(const Scene& scene);

}  // namespace mallet
