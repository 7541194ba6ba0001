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
