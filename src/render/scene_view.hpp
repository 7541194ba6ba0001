#pragma once
// What is drawn where, as pure maths (no GPU): the off-axis perspective that shows the
// scene's screen_to_world rectangle of the mallet's plane, framed for the image's
// proportions (unstretched, the rest filled with more of the world), and the placement of
// every model instance (bars scaled from their unit model, rails under the nodal points,
// the mallet head).
#include <algorithm>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/geometry.hpp"
#include "core/scene.hpp"

namespace mallet::render {

//! Vulkan clip space (y down, depth 0..1) for an image of `aspect` (width over height; 0:
//! the content's own). A world point on the plane z = 0 projects to the same normalised
//! screen position as framed(scene.screen_to_world, aspect).unmap gives for it.
glm::mat4 view_projection(const Scene& scene, double aspect = 0, double near_m = 0.05, double far_m = 20.0);

//! The mallet's sphere as seen from straight in front of its centre: the same frustum
//! through the same framed rectangle, from the eye moved parallel to the plane z = 0 until
//! it faces `centre`. The plane z = 0 maps onto the image exactly as in view_projection (the
//! window lies in it) and depth is the same function of z, so the sphere sits where it did
//! and meets the bars as before; but it is seen along its own axis, so it is drawn round
//! anywhere on screen instead of the ellipse that the off-axis view stretches it into away
//! from the eye's axis (1.15 times taller than wide at the percussion scene's bottom edge).
glm::mat4 sphere_view_projection(const Scene& scene, double aspect, Vec2 centre, double near_m = 0.05,
                                 double far_m = 20.0);
glm::vec3 eye_position(const Scene& scene);

//! Where the sphere's centre appears on screen (0..1, origin top-left), for checks.
glm::dvec2 project_to_screen(const glm::mat4& view_proj, glm::dvec3 world);

struct Instance {
  std::string model;   //!< file name in models/
  glm::mat4 transform; //!< model → world
  int target = -1;     //!< the bar's id, or -1
  glm::vec3 glow_color{0.0f};  //!< a bar's: its material's glow_srgb, linear (the light it gives off when lit)
};

//! An sRGB colour component (0..1) as linear light.
double srgb_to_linear(double c);

//! The nodal points of a free bar's first mode, as a fraction of its length from each end:
//! where real instruments support their bars (rails, cords).
inline constexpr double kNodalPoint = 0.224;

//! The texture scene's disc: radius 1 in the plane z = 0 facing the viewer, scaled to the relief.
inline constexpr const char* kTextureDiscModel = "texture_disc.glb";

//! Bars and rails of every instrument, the wall, the texture's disc (static for a scene).
std::vector<Instance> instrument_instances(const Scene& scene);

//! The mallet head (Scene::mallet_model): a unit sphere scaled to the scene's radius at `centre` (plane z = 0).
Instance mallet_instance(const Scene& scene, Vec2 centre);

//! How much larger than the head its model is drawn: a hull whose pixels the renderer shades
//! as the exact sphere (scene's sphere.frag: the ray through each pixel meets it or not), with
//! a margin for the antialiased edge. The shipped 48 × 22 sphere's outline lies within
//! cos(π/22) ≈ 0.99 of its radius: scaled by 1.25 it reaches a quarter of the radius beyond
//! the head, more than a pixel at every size the goldens and the kiosk draw it.
inline constexpr double kMalletHullScale = 1.25;
//! mallet_instance() scaled by kMalletHullScale about the centre: what is rasterised.
Instance mallet_hull(const Scene& scene, Vec2 centre);

//! The direction towards the key light (unit, world): nearly overhead and a little in front
//! for the instruments, so that the sphere's shadow falls just behind the point under it,
//! where the eye (above and in front) sees it; from in front and a little above for the
//! second paper's texture, whose disc faces the visitor: from above, the cursor's shadow
//! on the disc a radius behind it would be drawn out into a streak nearly 5 times as long
//! as the cursor is wide (the light grazing the disc at 12°), and the disc, lit edge on,
//! would be grey.
glm::dvec3 key_light_direction(const Scene& scene);

//! An axis-aligned box in world metres; empty until a point is added.
struct Box {
  glm::dvec3 lo{1e300}, hi{-1e300};
  void add(glm::dvec3 p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  //! Corner i (0..7): bit 0 picks x from hi, bit 1 y, bit 2 z.
  glm::dvec3 corner(int i) const { return {i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z}; }
};

//! The pixels [x0, x1) × [y0, y1) of an image.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};

//! The sphere that casts the only shadow, and the disc light it blocks: the terms of the
//! scene shader's sphere_visibility().
struct SphereShadow {
  glm::dvec3 centre{0.0};
  double radius = 0;            //!< 0: no shadow
  glm::dvec3 to_light{0, 1, 0}; //!< unit vector towards the light
  double tan_radius = 0;        //!< tangent of the light's angular radius
};

//! A point's visibility of the light past the sphere (1 lit, 0 in the umbra), as the scene
//! shader computes it in floats; here in doubles, for checks.
double sphere_visibility(const SphereShadow& s, glm::dvec3 p);

//! The pixels a world box covers on a width × height image (its eight corners projected,
//! two pixels of margin, clamped); the whole image when the box reaches behind the eye,
//! nothing for an empty box.
PixelRect screen_rect(const glm::mat4& view_proj, int width, int height, const Box& box);
inline bool overlap(const PixelRect& a, const PixelRect& b) {
  return !a.empty() && !b.empty() && a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}
//! The pixels in both (empty when they do not overlap).
inline PixelRect intersection(const PixelRect& a, const PixelRect& b) {
  const PixelRect r{std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
  return r.empty() ? PixelRect{} : r;
}
//! The smallest rectangle holding both (either may be empty).
inline PixelRect bounding(const PixelRect& a, const PixelRect& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

//! A screen rectangle (clamped to width × height) outside which the sphere darkens nothing
//! inside `receivers`: every point of the box with visibility < 1 projects into it. Empty
//! when the sphere shadows nothing there; the whole image when the region reaches behind
//! the eye. The renderer changes only these pixels of its cached background for the shadow.
PixelRect shadow_bounds(const glm::mat4& view_proj, int width, int height, const SphereShadow& s,
                        const Box& receivers);

}  // namespace mallet::render
