#version 450
// The mallet's shadow over the cached background, shaded on the screen: each pixel's point
// on the instruments comes back from the cached depth, its visibility of the light is the
// same analytic test as scene.frag's, and its colour is the cached unshadowed light less the
// share the shadow takes (scene.frag's result for the same point), whatever the models'
// triangle count.
#extension GL_GOOGLE_include_directive : require
#include "frame_uniform.glsl"
#include "sphere_shadow.glsl"

layout(set = 1, binding = 0) uniform sampler2D unshadowed;
layout(set = 1, binding = 1) uniform sampler2D shadow_share;
layout(set = 1, binding = 2) uniform sampler2D depth;

layout(push_constant) uniform Unproject {
  mat4 inverse_view_proj;  // clip space → world, for the image size the cache was drawn at
  vec4 inverse_size;       // xy: 1 / the image's width and height in pixels
} unproject;

layout(location = 0) out vec4 out_color;

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  float z = texelFetch(depth, texel, 0).r;
  if (z >= 1.0) discard;  // no instrument here: the room, as cached
  vec2 ndc = gl_FragCoord.xy * unproject.inverse_size.xy * 2.0 - 1.0;
  vec4 world = unproject.inverse_view_proj * vec4(ndc, z, 1.0);
  float visibility = sphere_visibility(world.xyz / world.w);
  if (visibility >= 1.0) discard;  // lit: the cached pixel is already right
  vec4 lit = texelFetch(unshadowed, texel, 0);
  out_color = vec4(lit.rgb - (1.0 - visibility) * texelFetch(shadow_share, texel, 0).rgb, lit.a);
}
