#version 450
// The mallet head as the exact sphere (frame.mallet), whatever its model's triangles: the
// model is drawn a little larger (kMalletHullScale, scene_view.hpp) as a hull, and each of
// its pixels looks along its ray from the eye of frame.sphere_view_proj (straight in front of
// the centre). A ray that meets the sphere is shaded at the point it meets, with the
// sphere's own normal there, and writes that point's depth; the pixel's coverage is how far
// inside the outline its ray passes, in pixels, so the edge is antialiased at any sample
// count (the pipeline blends by alpha). A ray that misses by more than half a pixel draws
// nothing.
#extension GL_GOOGLE_include_directive : require
#include "scene_common.glsl"

layout(set = 1, binding = 0) uniform sampler2D base_color_texture;

#include "surface_light.glsl"

layout(location = 0) in vec3 world_position;  // on the hull
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec2 uv;

layout(location = 0) out vec4 out_color;

// soft_terminator's w for the head: its terminator spread over about ±14°.
const float kTerminatorWidth = 0.25;

void main() {
  vec3 centre = frame.mallet.xyz;
  float radius = frame.mallet.w;
  vec3 eye = vec3(centre.xy, frame.eye.z);  // sphere_view_projection's eye
  vec3 ray = normalize(world_position - eye);
  float along = dot(centre - eye, ray);
  vec3 nearest = eye + along * ray;  // the ray's point nearest the centre
  float miss = length(nearest - centre);
  // The outline is where miss = radius; miss changes by about `pixel` from one pixel to the next.
  float pixel = max(length(vec2(dFdx(miss), dFdy(miss))), 1e-7);
  float coverage = clamp(0.5 - (miss - radius) / pixel, 0.0, 1.0);
  if (coverage <= 0.0) discard;
  vec3 n;
  vec3 point;
  if (miss < radius) {
    point = eye + (along - sqrt(radius * radius - miss * miss)) * ray;
    n = (point - centre) / radius;
  } else {  // just outside the outline: the outline's own point, for the edge's colour
    n = (nearest - centre) / max(miss, 1e-9);
    point = centre + radius * n;
  }
  vec4 clip = frame.sphere_view_proj * vec4(point, 1.0);
  gl_FragDepth = clip.z / clip.w;
  SurfaceLight s = surface_light(point, n, uv, kTerminatorWidth);
  // The head receives no shadow (it casts the only one).
  out_color = vec4(s.direct + s.ambient + draw.emissive.rgb, s.alpha * coverage);
}
