#version 450
// The cached background's light, per pixel, for the shadow shaded on the screen
// (shadow.frag): drawn once per image size with the instruments, at one sample a pixel, with
// which bar each pixel shows (for a detailed bar's glow when it is lit).
#extension GL_GOOGLE_include_directive : require
#include "scene_common.glsl"

layout(set = 1, binding = 0) uniform sampler2D base_color_texture;

#include "surface_light.glsl"

layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec2 uv;

layout(location = 0) out vec4 out_unshadowed;    // the pixel as scene.frag shades it with no shadow
layout(location = 1) out vec4 out_shadow_share;  // rgb: what a full shadow takes from it; a: the bar's id + 1 (0: no bar)

void main() {
  SurfaceLight s = surface_light(world_position, world_normal, uv);
  out_unshadowed = vec4(s.direct + s.ambient + draw.emissive.rgb, s.alpha);
  out_shadow_share = vec4(s.direct + (1.0 - kShadowedAmbient) * s.ambient, draw.emissive.w);
}
