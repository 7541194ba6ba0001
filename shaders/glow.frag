#version 450
// A lit bar's glow over the cached background of single-sampled frames: the light the bar
// gives off, added (blend ONE, ONE) to its pixels as the cache and the shadow's pass left
// them. scene.frag adds the same emissive term to the same light (surface_light.glsl), so a
// lit bar costs a constant per pixel here instead of its whole shading.
#extension GL_GOOGLE_include_directive : require
#include "scene_common.glsl"

// scene.vert's outputs, declared so that the two stages' interfaces match (unread here).
layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec2 uv;

layout(location = 0) out vec4 out_color;

void main() { out_color = vec4(draw.emissive.rgb, 0.0); }
