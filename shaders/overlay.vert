#version 450
// The 2D overlay: positions in pixels (origin top-left, y down) → clip space.
layout(push_constant) uniform Viewport { vec2 size; } viewport;

layout(location = 0) in vec2 in_position;
layout(location = 1) in vec2 in_uv;
layout(location = 2) in vec4 in_color;

layout(location = 0) out vec2 uv;
layout(location = 1) out vec4 color;

void main() {
  uv = in_uv;
  // Colours are given in sRGB (as designers pick them); the target blends in linear.
  color = vec4(pow(in_color.rgb, vec3(2.2)), in_color.a);
  gl_Position = vec4(in_position / viewport.size * 2.0 - 1.0, 0.0, 1.0);
}
