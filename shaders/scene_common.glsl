// Shared by scene.vert and scene.frag: the per-frame uniform and per-draw push constants.
layout(set = 0, binding = 0) uniform Frame {
  mat4 view_proj;
  vec4 eye;          // xyz: the eye in world metres
  vec4 light_dir;    // xyz: unit vector towards the light; w: tan of the light's angular radius
  vec4 sphere;       // xyz: the mallet head's centre; w: its radius (0 = no shadow)
  vec4 light_color;  // rgb: the key light; w: ambient strength
  mat4 sphere_view_proj;  // the mallet seen from straight in front of it: drawn round anywhere on screen
} frame;

layout(push_constant) uniform Draw {
  mat4 model;
  vec4 base_color;   // linear RGBA factor
  vec4 params;       // x metallic, y roughness, w textured (0/1); z the sphere's shadow: 0 not received,
                     // 1 received, 2 received and only the pixels it darkens drawn (over the cached background),
                     // -1 the sphere itself (not received; projected by frame.sphere_view_proj)
  vec4 emissive;     // rgb: light the surface gives off (a lit bar: under the mallet, or struck)
} draw;
