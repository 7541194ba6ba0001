#version 450
#extension GL_GOOGLE_include_directive : require
#include "scene_common.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;

layout(location = 0) out vec3 world_position;
layout(location = 1) out vec3 world_normal;
layout(location = 2) out vec2 uv;

void main() {
  vec4 world = draw.model * vec4(in_position, 1.0);
  world_position = world.xyz;
  // Bars are scaled non-uniformly: normals go through the inverse transpose.
  world_normal = transpose(inverse(mat3(draw.model))) * in_normal;
  uv = in_uv;
  gl_Position = (draw.params.z < -0.5 ? frame.sphere_view_proj : frame.view_proj) * world;
}
