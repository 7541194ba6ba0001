#include "render/scene_view.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace mallet::render {

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

glm::dvec3 key_light_direction(const Scene& scene) {
  if (scene.kind == SceneKind::texture) return glm::normalize(glm::dvec3(0.0, 0.35, 1.0));
  return glm::normalize(glm::dvec3(0.0, 1.0, 0.22));
}

glm::vec3 eye_position(const Scene& scene) {
  return {static_cast<float>(scene.camera.eye_x_m), static_cast<float>(scene.camera.eye_y_m),
          static_cast<float>(scene.camera.eye_z_m)};
}

namespace {

//! The off-axis frustum from `c`'s eye through the rectangle `w` of the plane z = 0.
glm::mat4 frustum_through(const ScreenToWorld& w, const Camera& c, double near_m, double far_m) {
  // The window is the rectangle on the plane z = 0, at distance eye_z in front of the eye,
  // which looks straight down −z: an asymmetric frustum through it.
  const double k = near_m / c.eye_z_m;
  const double l = (w.left_m - c.eye_x_m) * k, r = (w.right_m - c.eye_x_m) * k;
  const double b = (w.bottom_m - c.eye_y_m) * k, t = (w.top_m - c.eye_y_m) * k;
  glm::dmat4 p(0.0);
  p[0][0] = 2 * near_m / (r - l);
  p[1][1] = -2 * near_m / (t - b);  // Vulkan's y points down
  p[2][0] = (r + l) / (r - l);
  p[2][1] = -(t + b) / (t - b);
  p[2][2] = far_m / (near_m - far_m);
  p[2][3] = -1;
  p[3][2] = near_m * far_m / (near_m - far_m);
  const glm::dmat4 view = glm::translate(glm::dmat4(1.0), -glm::dvec3(c.eye_x_m, c.eye_y_m, c.eye_z_m));
  return glm::mat4(p * view);
}

}  // namespace

glm::mat4 view_projection(const Scene& scene, double aspect, double near_m, double far_m) {
  return frustum_through(framed(scene.screen_to_world, aspect), scene.camera, near_m, far_m);
}

glm::mat4 sphere_view_projection(const Scene& scene, double aspect, Vec2 centre, double near_m, double far_m) {
  Camera facing = scene.camera;
  facing.eye_x_m = centre.x;
  facing.eye_y_m = centre.y;
  return frustum_through(framed(scene.screen_to_world, aspect), facing, near_m, far_m);
}

glm::dvec2 project_to_screen(const glm::mat4& view_proj, glm::dvec3 world) {
  const glm::dvec4 clip = glm::dmat4(view_proj) * glm::dvec4(world, 1.0);
  return {(clip.x / clip.w + 1) / 2, (clip.y / clip.w + 1) / 2};
}

std::vector<Instance> instrument_instances(const Scene& scene) {
  std::vector<Instance> out;
  if (scene.texture) {  // the white disc, just behind the cursor's plane so the cursor's shadow falls on it
    // Set back by the cursor's radius, and enlarged about the eye's axis by the same
    // perspective factor, so that on screen it covers exactly the disc of the plane z = 0
    // that TextureRelief::covers() describes.
    const TextureRelief& r = scene.texture->relief;
    const double depth = scene.mallet_radius_m;
    const double k = (scene.camera.eye_z_m + depth) / scene.camera.eye_z_m;
    const glm::dvec3 centre{scene.camera.eye_x_m + (r.center.x - scene.camera.eye_x_m) * k,
                            scene.camera.eye_y_m + (r.center.y - scene.camera.eye_y_m) * k, -depth};
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), centre);
    m = glm::scale(m, {r.radius_m * k, r.radius_m * k, 1.0});
    out.push_back({kTextureDiscModel, glm::mat4(m), -1});
  }
  for (const Instrument& inst : scene.instruments) {
    if (inst.targets.empty()) continue;
    for (int id : inst.targets) {
      const Target& bar = scene.targets.at(id);
      glm::dmat4 m = glm::translate(glm::dmat4(1.0), {(bar.x_min + bar.x_max) / 2, bar.top_y, 0.0});
      m = glm::scale(m, {bar.x_max - bar.x_min, bar.thickness_m, bar.length_m});
      const std::array<double, 3>& glow = scene.material_of(bar).glow_srgb;
      out.push_back({inst.bar_model, glm::mat4(m), bar.id,
                     glm::vec3(static_cast<float>(srgb_to_linear(glow[0])), static_cast<float>(srgb_to_linear(glow[1])),
                               static_cast<float>(srgb_to_linear(glow[2])))});
    }
    if (inst.rail_model.empty()) continue;  // the wall stands alone
    // Two rails under the bars' nodal points, from the first bar to the last: graded
    // lengths make them converge, as on a real frame.
    const Target& first = scene.targets.at(inst.targets.front());
    const Target& last = scene.targets.at(inst.targets.back());
    const double rail_height = 0.03, rail_width = 0.016, overhang = 0.02;
    for (double side : {-1.0, 1.0}) {
      const double z0 = side * (0.5 - kNodalPoint) * first.length_m;
      const double z1 = side * (0.5 - kNodalPoint) * last.length_m;
      const glm::dvec3 a{first.x_min - overhang, first.top_y - first.thickness_m, z0};
      const glm::dvec3 b{last.x_max + overhang, last.top_y - last.thickness_m, z1};
      const double length = std::hypot(b.x - a.x, b.z - a.z);
      const double yaw = std::atan2(-(b.z - a.z), b.x - a.x);  // rotation about +y maps +x to (cos, 0, −sin)
      glm::dmat4 m = glm::translate(glm::dmat4(1.0), a);
      m = glm::rotate(m, yaw, {0.0, 1.0, 0.0});
      m = glm::scale(m, {length, rail_height, rail_width});
      out.push_back({inst.rail_model, glm::mat4(m), -1});
    }
  }
  return out;
}

Instance mallet_instance(const Scene& scene, Vec2 centre) {
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), {centre.x, centre.y, 0.0});
  m = glm::scale(m, glm::dvec3(scene.mallet_radius_m));
  return {scene.mallet_model, glm::mat4(m), -1};
}

Instance mallet_hull(const Scene& scene, Vec2 centre) {
  Instance hull = mallet_instance(scene, centre);
  hull.transform = hull.transform * glm::scale(glm::mat4(1.0f), glm::vec3(static_cast<float>(kMalletHullScale)));
  return hull;
}

double sphere_visibility(const SphereShadow& s, glm::dvec3 p) {
  if (s.radius <= 0) return 1;
  const glm::dvec3 to_centre = s.centre - p;
  const double along = glm::dot(to_centre, s.to_light);
  if (along <= 0) return 1;
  const double miss = glm::length(to_centre - along * s.to_light);
  const double penumbra = std::max(along * s.tan_radius, 1e-5);
  const double t = std::clamp((miss - (s.radius - penumbra)) / (2 * penumbra), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

PixelRect shadow_bounds(const glm::mat4& view_proj, int width, int height, const SphereShadow& s,
                        const Box& receivers) {
  if (s.radius <= 0 || receivers.empty() || width <= 0 || height <= 0) return {};
  // A shadowed point p lies `along` > 0 behind the centre, seen from the light, and
  // within radius + penumbra(along) of the axis. Inside the box `along` is at most the
  // largest over its corners, so every such point is within R of the segment from the
  // centre to that depth: in the box around the segment's two ends grown by R.
  double along_max = 0;
  for (int i = 0; i < 8; ++i) along_max = std::max(along_max, glm::dot(s.centre - receivers.corner(i), s.to_light));
  if (along_max <= 0) return {};
  const double reach = s.radius + std::max(along_max * s.tan_radius, 1e-5) + 1e-6;
  const glm::dvec3 end = s.centre - along_max * s.to_light;
  Box region;
  region.lo = glm::max(glm::min(s.centre, end) - reach, receivers.lo);
  region.hi = glm::min(glm::max(s.centre, end) + reach, receivers.hi);
  return screen_rect(view_proj, width, height, region);
}

PixelRect screen_rect(const glm::mat4& view_proj, int width, int height, const Box& box) {
  if (box.empty() || width <= 0 || height <= 0) return {};
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (int i = 0; i < 8; ++i) {
    const glm::dvec4 clip = glm::dmat4(view_proj) * glm::dvec4(box.corner(i), 1.0);
    if (clip.w <= 1e-9) return {0, 0, width, height};  // reaches behind the eye
    const double x = (clip.x / clip.w + 1) / 2 * width, y = (clip.y / clip.w + 1) / 2 * height;
    x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  }
  // Two pixels of margin: a fragment is shaded at its centre, and float rounding.
  auto clamp_to = [](double v, int hi) { return static_cast<int>(std::clamp(v, 0.0, static_cast<double>(hi))); };
  PixelRect r{clamp_to(std::floor(x0) - 2, width), clamp_to(std::floor(y0) - 2, height),
              clamp_to(std::ceil(x1) + 2, width), clamp_to(std::ceil(y1) + 2, height)};
  return r.empty() ? PixelRect{} : r;
}

}  // namespace mallet::render
