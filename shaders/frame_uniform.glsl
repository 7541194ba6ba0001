// The per-frame uniform: camera, light and the mallet sphere (scene.*, gbuffer.frag, shadow.frag).
layout(set = 0, binding = 0) uniform Frame {
  mat4 view_proj;
  vec4 eye;          // xyz: the eye in world metres
  vec4 light_dir;    // xyz: unit vector towards the light; w: tan of the light's angular radius
  vec4 sphere;       // xyz: the mallet head's centre; w: its radius (0 = no shadow)
  vec4 light_color;  // rgb: the key light; w: ambient strength
  mat4 sphere_view_proj;  // the mallet seen from straight in front of it: drawn round anywhere on screen
  vec4 mallet;       // xyz: the mallet head's centre; w: its radius (sphere.frag: drawn, whether it casts a shadow or not)
} frame;
