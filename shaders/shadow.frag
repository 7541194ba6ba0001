#version 450
// The mallet's shadow, and the glow of a lit detailed bar, over the cached background, shaded
// on the screen: each pixel's point on the instruments comes back from the cached depth, its
// visibility of the light is the same analytic test as scene.frag's, and its colour is the
// cached unshadowed light less the share the shadow takes, plus the glow where it shows a lit
// bar (scene.frag's result for the same point), whatever the models' triangle count.
#extension GL_GOOGLE_include_directive : require
#include "frame_uniform.glsl"
#include "sphere_shadow.glsl"

layout(set = 1, binding = 0) uniform sampler2D unshadowed;
layout(set = 1, binding = 1) uniform sampler2D shadow_share;
layout(set = 1, binding = 2) uniform sampler2D depth;

layout(push_constant) uniform Unproject {
  mat4 inverse_view_proj;  // clip space → world, for the image size the cache was drawn at
  vec4 inverse_size;       // xy: 1 / the image's width and height in pixels
  vec4 lit_a;              // a lit bar shaded here: x its id + 1 (0: none); yzw the light it gives off
  vec4 lit_b;              // the other, the same
  vec4 shadow_rect;        // where the shadow can fall, pixels: x0, y0, x1, y1 (empty: nowhere)
} unproject;

layout(location = 0) out vec4 out_color;

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  vec4 share = texelFetch(shadow_share, texel, 0);
  vec3 glow = vec3(0.0);
  if (share.a > 0.5) {
    if (abs(share.a - unproject.lit_a.x) < 0.5) glow = unproject.lit_a.yzw;
    if (abs(share.a - unproject.lit_b.x) < 0.5) glow = max(glow, unproject.lit_b.yzw);
  }
  bool lit = any(greaterThan(glow, vec3(0.0)));
  bool shadowed = all(greaterThanEqual(gl_FragCoord.xy, unproject.shadow_rect.xy)) &&
                  all(lessThan(gl_FragCoord.xy, unproject.shadow_rect.zw));
  if (!lit && !shadowed) discard;  // in a lit bar's rectangle, not on it
  float visibility = 1.0;
  if (shadowed) {
    float z = texelFetch(depth, texel, 0).r;
    if (z >= 1.0) discard;  // no instrument here: the room, as cached
    vec2 ndc = gl_FragCoord.xy * unproject.inverse_size.xy * 2.0 - 1.0;
    vec4 world = unproject.inverse_view_proj * vec4(ndc, z, 1.0);
    visibility = sphere_visibility(world.xyz / world.w);
  }
  if (visibility >= 1.0 && !lit) discard;  // the cached pixel is already right
  vec4 light = texelFetch(unshadowed, texel, 0);
  out_color = vec4(light.rgb - (1.0 - visibility) * share.rgb + glow, light.a);
}
