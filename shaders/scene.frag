#version 450
#extension GL_GOOGLE_include_directive : require
#include "scene_common.glsl"

layout(set = 1, binding = 0) uniform sampler2D base_color_texture;

layout(location = 0) in vec3 world_position;
layout(location = 1) in vec3 world_normal;
layout(location = 2) in vec2 uv;

layout(location = 0) out vec4 out_color;

const float PI = 3.14159265;

// The only shadow caster is the mallet head, a sphere: a point is in its shadow when the
// ray towards the light passes within the radius of the centre. The light has an angular
// radius, so the edge is a penumbra whose width grows with the distance to the sphere —
// exact for a sphere and a distant disc light up to the smoothstep profile, and free of
// shadow-map texels, bias and acne.
float sphere_visibility(vec3 p) {
  float radius = frame.sphere.w;
  if (radius <= 0.0) return 1.0;
  vec3 to_centre = frame.sphere.xyz - p;
  float along = dot(to_centre, frame.light_dir.xyz);
  if (along <= 0.0) return 1.0;  // the sphere is behind the point, seen from the light
  float miss = length(to_centre - along * frame.light_dir.xyz);
  float penumbra = max(along * frame.light_dir.w, 1e-5);
  return smoothstep(radius - penumbra, radius + penumbra, miss);
}

float ggx(float n_dot_h, float roughness) {
  float a2 = roughness * roughness * roughness * roughness;
  float d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
  return a2 / (PI * d * d);
}

void main() {
  float visibility = draw.params.z > 0.5 ? sphere_visibility(world_position) : 1.0;
  // Redrawn over the cached background: an unshadowed pixel is already there, as it is.
  if (draw.params.z > 1.5 && visibility >= 1.0) discard;

  vec4 albedo = draw.base_color;
  if (draw.params.w > 0.5) albedo *= texture(base_color_texture, uv);
  float metallic = clamp(draw.params.x, 0.0, 1.0);
  float roughness = clamp(draw.params.y, 0.05, 1.0);

  vec3 n = normalize(world_normal);
  vec3 v = normalize(frame.eye.xyz - world_position);
  vec3 l = frame.light_dir.xyz;
  vec3 h = normalize(l + v);
  float n_dot_l = max(dot(n, l), 0.0);
  float n_dot_v = max(dot(n, v), 1e-4);

  vec3 f0 = mix(vec3(0.04), albedo.rgb, metallic);
  vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - max(dot(h, v), 0.0), 5.0);
  float k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
  float geometry = n_dot_l / (n_dot_l * (1.0 - k) + k) * n_dot_v / (n_dot_v * (1.0 - k) + k);
  vec3 specular = ggx(max(dot(n, h), 0.0), roughness) * fresnel * geometry / (4.0 * n_dot_v + 1e-4);
  vec3 diffuse = (1.0 - metallic) * (1.0 - fresnel) * albedo.rgb / PI;
  vec3 direct = (diffuse + specular) * frame.light_color.rgb * n_dot_l * visibility;

  // A room around the instruments: a bright ceiling and a dark floor, reflected by metal
  // and lighting everything softly. The sphere darkens the ambient light under it too.
  vec3 r = reflect(-v, n);
  vec3 sky = vec3(0.60, 0.62, 0.66), ground = vec3(0.10, 0.09, 0.08);
  vec3 environment = mix(ground, sky, smoothstep(-0.3, 0.6, mix(r.y, n.y, roughness)));
  vec3 ambient_diffuse = (1.0 - metallic) * albedo.rgb * mix(ground, sky, n.y * 0.5 + 0.5);
  vec3 ambient = (ambient_diffuse + environment * f0 * (1.0 - 0.7 * roughness)) * frame.light_color.w;
  ambient *= mix(0.55, 1.0, visibility);

  out_color = vec4(direct + ambient + draw.emissive.rgb, albedo.a);
}
