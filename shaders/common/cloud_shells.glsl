// Where a ray meets the spherical cloud shells: the view march's intervals through them
// (volumetric_clouds.comp), where the temporal reuse's and the upsampling's rays reach them
// (cloud_temporal.comp, cloud_upsample.comp), where a light path or the shadow map's rays
// leave them (the light march, cloud_shadow.comp). One formulation for every caller. A ray is
// given by the altitude h of its start above a planet of radius R and mu, the cosine of its
// zenith angle there; a sphere of altitude s is met at t^2 + 2 b t + k = 0 with b = (R + h) mu
// and k = (h - s)(2 R + h + s), written so nothing cancels in float (Earth-sized radii squared
// would leave metres of error).
#ifndef SKY_CLOUD_SHELLS_GLSL
#define SKY_CLOUD_SHELLS_GLSL

// The two roots of t^2 + 2 b t + k = 0, smaller first; false if there are none.
bool cloudShellRoots(float b, float k, out vec2 t) {
  float disc = b * b - k;
  t = vec2(0.0);
  if (disc < 0.0) return false;
  float q = -(b + (b >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
  float other = q != 0.0 ? k / q : 0.0;
  t = vec2(min(q, other), max(q, other));
  return true;
}

// Where the ray (start at altitude h, zenith cosine mu) meets the sphere at altitude s.
bool cloudSphereRoots(float R, float h, float mu, float s, out vec2 t) {
  return cloudShellRoots((R + h) * mu, (h - s) * (2.0 * R + h + s), t);
}

// The intervals along the ray, before it meets the ground (altitude 0), where it lies between
// the altitudes base and top: up to two (a ray from inside the shell that dips below its base
// and comes back up has two). Returns the count; intervals in iv[0 .. count - 1] as (enter,
// exit), enter >= 0.
int cloudShellIntervals(float R, float h, float mu, float base, float top, out vec2 iv[2]) {
  iv[0] = vec2(0.0);
  iv[1] = vec2(0.0);
  // The top: the ray is below it over [t0, t1].
  vec2 outer;
  if (!cloudSphereRoots(R, h, mu, top, outer) || outer.y <= 0.0) return 0;
  float t0 = max(outer.x, 0.0), t1 = outer.y;
  // The ground ends the ray (a ray heading down from on, or in float just above, the ground
  // meets it at once).
  vec2 ground;
  if (cloudSphereRoots(R, h, mu, 0.0, ground) && (ground.x > 0.0 || mu < 0.0))
    t1 = min(t1, max(ground.x, 0.0));
  // The base: cut the part below it, [a0, a1], out of [t0, t1].
  vec2 inner;
  if (!cloudSphereRoots(R, h, mu, base, inner)) {
    iv[0] = vec2(t0, t1);
    return t1 > t0 ? 1 : 0;
  }
  int n = 0;
  if (inner.x > t0) iv[n++] = vec2(t0, min(inner.x, t1));
  if (inner.y < t1 && inner.y > t0) iv[n++] = vec2(max(inner.y, t0), t1);
  if (inner.y <= t0 || inner.x >= t1) {  // the part below the base lies outside [t0, t1]
    n = 0;
    iv[n++] = vec2(t0, t1);
  }
  return n;
}

// The distance along the ray at which it first lies between the altitudes base and top before
// meeting the ground; 0 inside them, -1 when it never does.
float cloudShellEntry(float R, float h, float base, float top, vec3 d) {
  vec2 iv[2];
  return cloudShellIntervals(R, h, d.z, base, top, iv) > 0 ? iv[0].x : -1.0;
}

// From a point between the altitudes base and top, the distance along the ray to where it
// leaves them: through the top, or through the base when it heads down far enough to meet it.
float cloudShellExit(float R, float h, float mu, float base, float top) {
  vec2 t;
  if (mu < 0.0 && cloudSphereRoots(R, h, mu, base, t) && t.y > 0.0) return max(t.x, 0.0);
  return cloudSphereRoots(R, h, mu, top, t) ? max(t.y, 0.0) : 0.0;
}

// How alike two rays are for the clouds they see, from where they reach the shells (e, -1 if
// never): 1 for the same, falling with the relative difference, nearly 0 when one meets the
// ground first and the other reaches the clouds.
float cloudShellAlike(float e, float entry) {
  return (e < 0.0) != (entry < 0.0) ? 1e-3
                                    : 1.0 / (1.0 + 4.0 * abs(e - entry) / max(max(e, entry), 100.0));
}

#endif
