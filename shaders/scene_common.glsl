// Shared by scene.vert and scene.frag: the per-frame uniform and per-draw push constants.
#include "frame_uniform.glsl"

layout(push_constant) uniform Draw {
  mat4 model;
  vec4 base_color;   // linear RGBA factor
  vec4 params;       // x metallic, y roughness, w textured (0/1); z the sphere's shadow: 0 not received,
                     // 1 received, 2 received and only the pixels it darkens drawn (over the cached background
                     // of multisampled frames), -1 the sphere itself (not received; projected by frame.sphere_view_proj)
  vec4 emissive;     // rgb: light the surface gives off (a lit bar: under the mallet, or struck)
} draw;
