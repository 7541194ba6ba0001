#version 450
// Glyph coverage (or the atlas's solid texel for shapes) times the vertex colour.
layout(set = 0, binding = 0) uniform sampler2D atlas;

layout(location = 0) in vec2 uv;
layout(location = 1) in vec4 color;

layout(location = 0) out vec4 out_color;

void main() { out_color = vec4(color.rgb, color.a * texture(atlas, uv).r); }
