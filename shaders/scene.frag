#version 450
#extension GL_GOOGLE_include_directive : require
#include "scene_common.glsl"

layout(set = 1, binding = 0) uniform sampler2D base_color_texture;

#include "sphere_shadow.glsl"
#include "surface_light.glsl"

layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec2 uv;

layout(location = 0) out vec4 out_color;

void main() {
  float visibility = draw.params.z > 0.5 ? sphere_visibility(world_position) : 1.0;
  // Redrawn over the cached background (multisampled frames): an unshadowed pixel is
  // already there, as it is.
  if (draw.params.z > 1.5 && visibility >= 1.0) discard;
  SurfaceLight s = surface_light(world_position, world_normal, uv);
  // The sphere darkens the ambient light under it too.
  out_color = vec4(s.direct * visibility + s.ambient * mix(kShadowedAmbient, 1.0, visibility) + draw.emissive.rgb,
                   s.alpha);
}
