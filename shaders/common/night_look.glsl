// The display's night look, the twin of engine/color/night_look.cpp (applyNightLook): as a
// scene dims the rods take over from the cones, so dim parts lose their colour toward a blue
// grey (Larson, Rushmeier & Piatko 1997's scotopic luminance, CIE 191:2010's mesopic limits).
#ifndef SKY_NIGHT_LOOK_GLSL
#define SKY_NIGHT_LOOK_GLSL

#define NIGHT_LOOK_CD_PER_UNIT 1.0e4  // renderer radiance unit (docs/lighting.md)
#define NIGHT_LOOK_SCOTOPIC_LIMIT 0.01
#define NIGHT_LOOK_PHOTOPIC_LIMIT 3.0

// The share of the cones' response at luminance cdPerM2 (photopicShare).
float nightLookPhotopicShare(float cdPerM2) {
  if (!(cdPerM2 > NIGHT_LOOK_SCOTOPIC_LIMIT)) return 0.0;
  if (cdPerM2 >= NIGHT_LOOK_PHOTOPIC_LIMIT) return 1.0;
  float t = log(cdPerM2 / NIGHT_LOOK_SCOTOPIC_LIMIT) /
            log(NIGHT_LOOK_PHOTOPIC_LIMIT / NIGHT_LOOK_SCOTOPIC_LIMIT);
  return t * t * (3.0 - 2.0 * t);
}

// One pixel of applyNightLook: linear Rec.709 in the renderer's units.
vec3 nightLook(vec3 rgb) {
  vec3 c = max(rgb, vec3(0.0));
  float X = dot(c, vec3(0.4124, 0.3576, 0.1805));
  float Y = dot(c, vec3(0.2126, 0.7152, 0.0722));
  float Z = dot(c, vec3(0.0193, 0.1192, 0.9505));
  float w = nightLookPhotopicShare(Y * NIGHT_LOOK_CD_PER_UNIT);
  if (w >= 1.0) return rgb;
  // Larson's scotopic luminance of D65 white per unit of its photopic luminance.
  const float whiteScotopic = 1.33 * (1.0 + (1.0 + 1.0889) / 0.9505) - 1.68;
  float V = X > 0.0 ? max(Y * (1.33 * (1.0 + (Y + Z) / X) - 1.68), 0.0) / whiteScotopic : 0.0;
  // The rods' blue grey, chromaticity (0.28, 0.29) at unit luminance, in linear Rec.709.
  const vec3 tintXYZ = vec3(0.28 / 0.29, 1.0, (1.0 - 0.28 - 0.29) / 0.29);
  vec3 tint = vec3(dot(tintXYZ, vec3(3.2406, -1.5372, -0.4986)),
                   dot(tintXYZ, vec3(-0.9689, 1.8758, 0.0415)),
                   dot(tintXYZ, vec3(0.0557, -0.2040, 1.0570)));
  return w * c + (1.0 - w) * V * tint;
}

#endif
