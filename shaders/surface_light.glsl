// The light a surface point receives with no shadow: the key light (direct) and the room's
// (ambient). The frames shade with it (scene.frag); the cached background keeps it per pixel
// (gbuffer.frag) so that the shadow can be shaded on the screen (shadow.frag).
// Needs base_color_texture (set 1) and the Draw push constants declared before it.

const float PI = 3.14159265;
// Under the sphere the room's light falls to this share (a soft contact darkening).
const float kShadowedAmbient = 0.55;

float ggx(float n_dot_h, float roughness) {
  float a2 = roughness * roughness * roughness * roughness;
  float d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
  return a2 / (PI * d * d);
}

struct SurfaceLight {
  vec3 direct;   // the key light, unshadowed
  vec3 ambient;  // the room's light
  float alpha;
};

// Lambert's max(n·l, 0) with its corner at the terminator rounded over ±w: the same light
// where n·l ≥ w, none where n·l ≤ −w, and between them a parabola that meets both with the
// same slope. On the sphere a corner in the light's slope shows as a hard band along the
// terminator (the eye sharpens it: Mach bands); a light of some size has none.
float soft_terminator(float n_dot_l, float w) {
  if (w <= 0.0) return max(n_dot_l, 0.0);
  if (n_dot_l >= w) return n_dot_l;
  if (n_dot_l <= -w) return 0.0;
  return (n_dot_l + w) * (n_dot_l + w) / (4.0 * w);
}

// terminator_width: soft_terminator's w for the diffuse light (0: Lambert's, as the bars
// have it: their faces are flat, they have no terminator).
SurfaceLight surface_light(vec3 world_position, vec3 world_normal, vec2 uv, float terminator_width) {
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
  vec3 diffuse = (1.0 - metallic) * (1.0 - fresnel) * albedo.rgb / PI * soft_terminator(dot(n, l), terminator_width);

  // A room around the instruments: a bright ceiling and a dark floor, reflected by metal
  // and lighting everything softly.
  vec3 r = reflect(-v, n);
  vec3 sky = vec3(0.60, 0.62, 0.66), ground = vec3(0.10, 0.09, 0.08);
  vec3 environment = mix(ground, sky, smoothstep(-0.3, 0.6, mix(r.y, n.y, roughness)));
  vec3 ambient_diffuse = (1.0 - metallic) * albedo.rgb * mix(ground, sky, n.y * 0.5 + 0.5);

  SurfaceLight s;
  s.direct = (diffuse + specular * n_dot_l) * frame.light_color.rgb;
  s.ambient = (ambient_diffuse + environment * f0 * (1.0 - 0.7 * roughness)) * frame.light_color.w;
  s.alpha = albedo.a;
  return s;
}

SurfaceLight surface_light(vec3 world_position, vec3 world_normal, vec2 uv) {
  return surface_light(world_position, world_normal, uv, 0.0);
}
