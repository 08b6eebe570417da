// Tileable (periodic) 3D noise for the baked cloud-noise textures (docs/cloud-noise.md).
//
// The same convention as noise.glsl: every function takes an integer lattice `period` per
// axis and repeats exactly when p moves by it, because the lattice hash only sees positions
// modulo the period. A texture of N texels tiles when it is evaluated at
// p = (texel + 0.5) / N * f with an integer frequency f and period f. Octave i of an fbm runs
// at 2^i times the frequency with 2^i times the period, so fbm tiles too. A `seed` (from
// noiseSeed) picks an independent field. Cell coordinates must stay within +-2^20.
//
// Contents: Perlin gradient noise with its analytic gradient, simplex noise on Gustavson and
// McEwan's periodic lattice, Worley F1, their fbm, and curl noise of a Perlin vector potential.
#ifndef SKY_NOISE3D_GLSL
#define SKY_NOISE3D_GLSL
#include "noise.glsl"

// A cell moved by less than one period outside [0, period), folded back without a division
// (integer division is slow on CPU Vulkan, and Worley needs 27 of these per evaluation).
ivec3 noiseWrapNear3(ivec3 cell, ivec3 period) {
  cell += period * ivec3(lessThan(cell, ivec3(0)));
  return cell - period * ivec3(greaterThanEqual(cell, period));
}

// The lattice cell `cell` folded into [0, period): what makes the noise periodic. The floor
// of the quotient comes from a float division, which may be one off next to an integer; the
// remainder is then one period out and noiseWrapNear3 puts it back. Exact for |cell| < 2^20.
ivec3 noiseWrap3(ivec3 cell, ivec3 period) {
  ivec3 q = ivec3(floor(vec3(cell) / vec3(period)));
  return noiseWrapNear3(cell - q * period, period);
}

// pcg3d of a wrapped cell and the seed, XORed into z: pcg3d mixes every input bit into every
// output, so distinct seeds give unrelated fields.
uvec3 noiseCellHash3(ivec3 wrapped, uint seed) {
  return noiseHash3(uvec3(uvec2(wrapped.xy), uint(wrapped.z) ^ seed));
}

// --- Perlin gradient noise ---

// Perlin's 12 gradients (the edges of a cube, length sqrt 2; Perlin 2002, "Improving Noise"),
// picked by the hash's top 4 bits with 4 of them twice, as in his reference implementation.
vec3 perlinGradient3(uint h) {
  h >>= 28u;
  float su = 1.0 - 2.0 * float(h & 1u);
  float sv = 1.0 - float(h & 2u);
  vec3 gu = mix(vec3(0.0, su, 0.0), vec3(su, 0.0, 0.0), bvec3(h < 8u));
  vec3 gv = mix(mix(vec3(0.0, 0.0, sv), vec3(sv, 0.0, 0.0), bvec3(h == 12u || h == 14u)),
                vec3(0.0, sv, 0.0), bvec3(h < 4u));
  return gu + gv;
}

// Perlin gradient noise, in about [-1, 1], and its gradient: (value, d/dx, d/dy, d/dz).
// Quintic fade (C2 across cells); the gradient is exact (Quilez, "gradient noise derivatives").
vec4 perlinNoise3d(vec3 p, ivec3 period, uint seed) {
  vec3 i = floor(p);
  vec3 f = p - i;
  ivec3 c = noiseWrap3(ivec3(i), period);
  ivec3 c1 = noiseWrapNear3(c + 1, period);
  vec3 ga = perlinGradient3(noiseCellHash3(ivec3(c.x, c.y, c.z), seed).x);
  vec3 gb = perlinGradient3(noiseCellHash3(ivec3(c1.x, c.y, c.z), seed).x);
  vec3 gc = perlinGradient3(noiseCellHash3(ivec3(c.x, c1.y, c.z), seed).x);
  vec3 gd = perlinGradient3(noiseCellHash3(ivec3(c1.x, c1.y, c.z), seed).x);
  vec3 ge = perlinGradient3(noiseCellHash3(ivec3(c.x, c.y, c1.z), seed).x);
  vec3 gf = perlinGradient3(noiseCellHash3(ivec3(c1.x, c.y, c1.z), seed).x);
  vec3 gg = perlinGradient3(noiseCellHash3(ivec3(c.x, c1.y, c1.z), seed).x);
  vec3 gh = perlinGradient3(noiseCellHash3(ivec3(c1.x, c1.y, c1.z), seed).x);
  float va = dot(ga, f);
  float vb = dot(gb, f - vec3(1.0, 0.0, 0.0));
  float vc = dot(gc, f - vec3(0.0, 1.0, 0.0));
  float vd = dot(gd, f - vec3(1.0, 1.0, 0.0));
  float ve = dot(ge, f - vec3(0.0, 0.0, 1.0));
  float vf = dot(gf, f - vec3(1.0, 0.0, 1.0));
  float vg = dot(gg, f - vec3(0.0, 1.0, 1.0));
  float vh = dot(gh, f - vec3(1.0, 1.0, 1.0));
  vec3 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
  vec3 du = 30.0 * f * f * (f * (f - 2.0) + 1.0);
  // Trilinear interpolation written as a polynomial in u, so its derivative is direct.
  float k1 = vb - va, k2 = vc - va, k3 = ve - va;
  float k4 = va - vb - vc + vd, k5 = va - vc - ve + vg, k6 = va - vb - ve + vf;
  float k7 = -va + vb + vc - vd + ve - vf - vg + vh;
  float value = va + u.x * k1 + u.y * k2 + u.z * k3 + u.x * u.y * k4 + u.y * u.z * k5 +
                u.z * u.x * k6 + u.x * u.y * u.z * k7;
  vec3 grad = ga + u.x * (gb - ga) + u.y * (gc - ga) + u.z * (ge - ga) +
              u.x * u.y * (ga - gb - gc + gd) + u.y * u.z * (ga - gc - ge + gg) +
              u.z * u.x * (ga - gb - ge + gf) +
              u.x * u.y * u.z * (-ga + gb + gc - gd + ge - gf - gg + gh) +
              du * (vec3(k1, k2, k3) + u.yzx * vec3(k4, k5, k6) + u.zxy * vec3(k6, k4, k5) +
                    k7 * u.yzx * u.zxy);
  return vec4(value, grad);
}

float perlinNoise3(vec3 p, ivec3 period, uint seed) {
  return perlinNoise3d(p, period, seed).x;
}

// --- Simplex noise, periodic ---
//
// Classic simplex noise skews space so that the simplex lattice's vertices are integer points
// of the skewed space; that lattice has no integer period along the x, y, z axes, so it cannot
// tile a cube. Gustavson and McEwan ("Tiling simplex flow noise in two and three dimensions",
// JCGT 11(1), 2022, psrdnoise) use instead the lattice of x = Mi * i (i integer,
// M = [[0,1,1],[1,0,1],[1,1,0]], Mi its inverse): the body-centred cubic lattice, i.e. the
// integer points plus the cube centres, split into tetrahedra by the Kuhn triangulation of
// the unit cubes of u = M x. That lattice maps onto itself under any integer translation, so
// folding each vertex's *position* into [0, period) before hashing makes the noise periodic
// with any integer period. Four vertices per point, each weighted by (0.5 - r^2)^3 (zero
// before the next vertex could matter), gradients uniform on the unit sphere.

// A unit vector uniform on the sphere from a hash: z uniform in [-1, 1], the angle uniform.
// The angle stays in [-pi, pi), where Vulkan bounds the error of sin and cos.
vec3 noiseUnitVector3(uvec3 h) {
  vec3 r = vec3(h >> 8u) * (1.0 / 16777216.0);
  float z = 1.0 - 2.0 * r.x;
  float s = sqrt(max(1.0 - z * z, 0.0));
  float angle = 6.28318530718 * r.y - 3.14159265359;
  return vec3(s * cos(angle), s * sin(angle), z);
}

// Simplex noise in about [-1, 1] (the 39.5 of psrdnoise scales the sum to that range).
float simplexNoise3(vec3 p, ivec3 period, uint seed) {
  vec3 uvw = vec3(p.y + p.z, p.x + p.z, p.x + p.y);  // M p
  vec3 i0f = floor(uvw);
  vec3 f0 = uvw - i0f;
  ivec3 i0 = ivec3(i0f);
  // Kuhn simplex of the cube: one unit step along each axis, largest fraction first.
  ivec3 o1 = ivec3(f0.x > f0.y && f0.x > f0.z, f0.y >= f0.x && f0.y > f0.z,
                   f0.z >= f0.x && f0.z >= f0.y);
  ivec3 o2 = ivec3(f0.x > f0.y || f0.x > f0.z, f0.y >= f0.x || f0.y > f0.z,
                   f0.z >= f0.x || f0.z >= f0.y);
  ivec3 corners[4] = ivec3[4](i0, i0 + o1, i0 + o2, i0 + 1);
  ivec3 period2 = 2 * period;
  float n = 0.0;
  for (int k = 0; k < 4; ++k) {
    ivec3 i = corners[k];
    // Twice the vertex position Mi * i: integers, all even (cube corner) or all odd (centre).
    ivec3 v2 = ivec3(i.y + i.z - i.x, i.x + i.z - i.y, i.x + i.y - i.z);
    vec3 x = p - 0.5 * vec3(v2);
    float w = max(0.5 - dot(x, x), 0.0);
    // The position folded into one period (in half units), then back to its lattice index
    // M * v, which identifies the vertex uniquely within the period.
    ivec3 v = noiseWrap3(v2, period2);
    ivec3 id = ivec3(v.y + v.z, v.x + v.z, v.x + v.y) / 2;
    vec3 g = noiseUnitVector3(noiseCellHash3(id, seed));
    n += w * w * w * dot(g, x);
  }
  return 39.5 * n;
}

// --- Worley (cellular) noise ---

// Worley 1996 F1: the distance (in cells) from p to the nearest of the feature points, one
// per cell anywhere inside it, searched over the 3x3x3 neighbourhood (a nearer point two
// cells away is possible but rare and changes F1 little).
float worleyF1(vec3 p, ivec3 period, uint seed) {
  vec3 i = floor(p);
  vec3 f = p - i;
  ivec3 c = noiseWrap3(ivec3(i), period);
  // The wrapped neighbour cells per axis, once: cells[k] is c + k - 1.
  ivec3 cells[3] = ivec3[3](noiseWrapNear3(c - 1, period), c, noiseWrapNear3(c + 1, period));
  float d2 = 8.0;
  for (int dz = 0; dz < 3; ++dz) {
    for (int dy = 0; dy < 3; ++dy) {
      for (int dx = 0; dx < 3; ++dx) {
        uvec3 h = noiseCellHash3(ivec3(cells[dx].x, cells[dy].y, cells[dz].z), seed);
        // 24-bit hashes convert to float exactly through int (a cheaper conversion than uint).
        vec3 d = vec3(dx - 1, dy - 1, dz - 1) + vec3(ivec3(h >> 8u)) * (1.0 / 16777216.0) - f;
        d2 = min(d2, dot(d, d));
      }
    }
  }
  return sqrt(d2);
}

// Inverted Worley, what clouds need: 1 at a feature point, falling to 0 one cell away.
float worleyInverted3(vec3 p, ivec3 period, uint seed) {
  return clamp(1.0 - worleyF1(p, period, seed), 0.0, 1.0);
}

// --- Fractal sums ---

// fbm of Perlin noise: `octaves` octaves, each at twice the frequency (and period) of the
// last and `gain` times its amplitude, each with its own seed; divided by the sum of the
// amplitudes, so it stays in about [-1, 1].
float perlinFbm3(vec3 p, ivec3 period, uint seed, int octaves, float gain) {
  float sum = 0.0, amplitude = 1.0, norm = 0.0;
  for (int i = 0; i < octaves; ++i) {
    sum += amplitude * perlinNoise3(p, period, noiseSeed(seed, uint(i)));
    norm += amplitude;
    amplitude *= gain;
    p *= 2.0;
    period *= 2;
  }
  return sum / norm;
}

// Tang (1): fbm = sum_i w^i noise(s^i x) of simplex noise with s = 2 (an integer ratio keeps
// every octave periodic) and w = `gain`, divided by sum_i w^i.
float simplexFbm3(vec3 p, ivec3 period, uint seed, int octaves, float gain) {
  float sum = 0.0, amplitude = 1.0, norm = 0.0;
  for (int i = 0; i < octaves; ++i) {
    sum += amplitude * simplexNoise3(p, period, noiseSeed(seed, uint(i)));  // Tang (1)
    norm += amplitude;
    amplitude *= gain;
    p *= 2.0;
    period *= 2;
  }
  return sum / norm;
}

// --- Curl noise ---

// Curl of a vector potential psi = (psi_x, psi_y, psi_z) whose components are independent
// Perlin fbm fields (Bridson et al. 2007, "Curl-noise for procedural fluid flow"):
// v = curl psi is divergence-free by construction. Derivatives are analytic, per unit of p;
// octave i adds gain^i * 2^i times its noise's gradient (the chain rule of p * 2^i), and the
// sum is divided by the sum of the gains like fbm. A caller scales the result to its range.
vec3 curlNoise3(vec3 p, ivec3 period, uint seed, int octaves, float gain) {
  vec3 dx = vec3(0.0), dy = vec3(0.0), dz = vec3(0.0);  // gradients of psi_x, psi_y, psi_z
  float amplitude = 1.0, norm = 0.0;
  for (int i = 0; i < octaves; ++i) {
    float scale = amplitude * float(1 << i);
    dx += scale * perlinNoise3d(p, period, noiseSeed(noiseSeed(seed, 0u), uint(i))).yzw;
    dy += scale * perlinNoise3d(p, period, noiseSeed(noiseSeed(seed, 1u), uint(i))).yzw;
    dz += scale * perlinNoise3d(p, period, noiseSeed(noiseSeed(seed, 2u), uint(i))).yzw;
    norm += amplitude;
    amplitude *= gain;
    p *= 2.0;
    period *= 2;
  }
  // curl psi = (d psi_z/dy - d psi_y/dz, d psi_x/dz - d psi_z/dx, d psi_y/dx - d psi_x/dy)
  return vec3(dz.y - dy.z, dx.z - dz.x, dy.x - dx.y) / norm;
}

#endif
