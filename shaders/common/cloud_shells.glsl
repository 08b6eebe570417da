// Where a view ray meets the cloud shells, for the passes that compare rays by it (the
// temporal reuse's and the upsampling's guide, cloud_temporal.comp and cloud_upsample.comp).
// Written so nothing cancels in float: a sphere is met at t^2 + 2 b t + k = 0 with
// k = (h - s)(2 R + h + s), the camera at altitude h and the sphere at altitude s above a
// planet of radius R.
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

// The distance along unit ray d (ENU at the camera) at which it first lies between the shells'
// altitudes base and top before meeting the ground; 0 inside them, -1 when it never does.
float cloudShellEntry(float R, float h, float base, float top, vec3 d) {
  if (h >= base && h <= top) return 0.0;
  float b = (R + h) * d.z;
  vec2 g;
  float ground = cloudShellRoots(b, h * (2.0 * R + h), g) && g.x > 0.0 ? g.x : 1e30;
  vec2 r;
  float t;
  if (h < base) {
    cloudShellRoots(b, (h - base) * (2.0 * R + h + base), r);  // inside it: leave upward
    t = r.y;
  } else {
    if (!cloudShellRoots(b, (h - top) * (2.0 * R + h + top), r) || r.x < 0.0) return -1.0;
    t = r.x;
  }
  return t < ground ? t : -1.0;
}

// How alike two rays are for the clouds they see, from where they reach the shells (e, -1 if
// never): 1 for the same, falling with the relative difference, nearly 0 when one meets the
// ground first and the other reaches the clouds.
float cloudShellAlike(float e, float entry) {
  return (e < 0.0) != (entry < 0.0) ? 1e-3
                                    : 1.0 / (1.0 + 4.0 * abs(e - entry) / max(max(e, entry), 100.0));
}

#endif
