#version 460
// Kernel for cloud_kernel_test.cpp: calls every function of shaders/common/cloud_density.glsl,
// cloud_lighting.glsl and cloud_light_march.glsl on a grid of inputs, one query per column.
// Rows 0-2 hold the inputs each query used (low-discrepancy values in [0, 1), and for the
// first queries fixed points), so the C++ side evaluates its twins on exactly those numbers.
// The row layout is KernelRow in the test.
#include <common/cloud_density.glsl>

#include <common/cloud_light_march.glsl>

// The light march's density (cloud_light_march.glsl asks the includer for it): a test field
// chosen per query. 0: constant 0.7; 1: linear ramp 0.3 + 0.0005 z; 2: a slab of 1 below z =
// gSlabTop and 0 above; 3: that slab, clear air above it up to gCloudBase (a gap longer than
// any step along the path), then 0.5 (a cloud, a gap, another cloud).
int gDensityKind = 0;
float gSlabTop = 0.0, gCloudBase = 0.0;
float cloudDensityForLight(CloudLightPath path, vec3 p, float lengthM, int part) {
  if (gDensityKind == 0) return 0.7;
  if (gDensityKind == 1) return 0.3 + 0.0005 * p.z;
  if (gDensityKind == 3 && p.z >= gCloudBase) return 0.5;
  return p.z < gSlabTop ? 1.0 : 0.0;
}

#define KERNEL_QUERIES 256
#define KERNEL_GROUP 64
layout(local_size_x = KERNEL_GROUP) in;
layout(binding = 0, rgba32f) uniform writeonly image2D results;

// Ei at tabulated points for the first queries (values in the test).
const float kEiPoints[8] = float[8](-1.0, -0.1, -5.0, -1e-4, -60.0, -1.5, -0.5, -20.0);

void put(int row, vec4 v) {
  imageStore(results, ivec2(gl_GlobalInvocationID.x, row), v);
}

void main() {
  int i = int(gl_GlobalInvocationID.x);
  // Additive recurrences with irrational steps: each input well spread over [0, 1).
  vec4 r0 = fract(0.5 + float(i) * vec4(0.8566748838545, 0.7338918566271, 0.6287067210378, 0.5385972572236));
  vec4 r1 = fract(0.5 + float(i) * vec4(0.4614032, 0.3952662, 0.3386080, 0.2900707));
  vec4 r2 = fract(0.5 + float(i) * vec4(0.2484897, 0.2128744, 0.1823663, 0.1562310));
  put(0, r0);
  put(1, r1);
  put(2, r2);

  // --- Lu (3)-(18) ---
  float ph = -0.1 + 1.2 * r0.x;  // a tenth outside the cloud on either side
  float cmc = r0.y;
  vec4 shape = vec4(r0.z, r0.w, r1.x, r1.y);
  vec3 detail = vec3(r1.z, r1.w, r2.x);
  float threshold = -0.5 + 1.6 * r2.y;  // [-0.5, 1.1): calibrated, paper and no-cloud thresholds
  float v = 2.0 * r2.z - 0.5;
  put(3, vec4(luRemap(v, r0.x, r0.x + 0.1 + r0.y, r1.x, r1.y), luSat(v), luLerp(r0.x, r0.y, v),
              luFbm(r0.z, r0.w, r1.x)));
  float gs = luGS(ph, cmc), gd = luGD(ph, cmc);
  put(4, vec4(luGSb(ph), luGSt(ph, cmc), gs, luGDb(ph)));
  float nstex = luNStex(shape);
  put(5, vec4(luGDt(ph), gd, nstex, luNS(nstex, gs, threshold, gd)));
  float ndfbm = luNDfbm(detail);
  float ndmod = luNDmod(ndfbm, cmc, ph);
  float nsfinal = luNSfinal(nstex, gs, threshold);
  put(6, vec4(ndfbm, ndmod, nsfinal, luDensity(nsfinal, ndmod, gd)));
  float type = -0.1 + 1.2 * r2.w;
  vec2 low = cloudTypeRange(0, type), mid = cloudTypeRange(1, type);
  put(7, vec4(luCloudDensity(shape, detail, ph, cmc, threshold),
              luCloudDensity(shape, detail, ph, cmc, 1.0 - cmc),
              cloudHeightFraction(r0.x, low), tangTypeGradient(ph, type)));
  put(8, vec4(low, mid));
  float base = tangBaseShape(shape, ph, type), erosion = tangErosion(ndfbm, ph);
  put(9, vec4(base, erosion, tangDensity(base, erosion, cmc, threshold),
              tangCloudDensity(shape, detail, ph, cmc, type, threshold)));

  // --- Lighting ---
  float b = 0.001 + 0.1 * r0.x, ds = 50.0 * r0.y, dsClamp = 50.0 * r0.z;
  float cosTheta = 2.0 * r0.w - 1.0;
  float g = 1.98 * r1.x - 0.99, gBack = -0.99 * r1.y, backWeight = r1.z;
  put(10, vec4(beerLambert(b, ds), beerClamped(b, ds, dsClamp), henyeyGreenstein(cosTheta, g),
               dualLobeHG(cosTheta, g, gBack, backWeight)));
  // Ei over [-60, -1e-4], log-uniform, after the tabulated points.
  float x = i < 8 ? kEiPoints[i] : -exp(mix(log(1e-4), log(60.0), r2.x));
  float a = i < 8 ? kEiPoints[i] : -exp(mix(log(1e-4), log(60.0), r2.z));
  float sigmaT = 0.001 + 0.05 * r1.w;
  vec3 ambient = cloudAmbient(r0.xyz, r1.xyz, sigmaT, 2000.0 * r2.w, 2000.0 * r0.w);
  put(11, vec4(expIntegralEi(x), slabAmbient(a), x, a));
  put(12, vec4(ambient, sigmaT));
  float tau = 10.0 * r0.x, tauClamp = 10.0 * r0.y;
  put(13, vec4(cloudInScatter(tau, tauClamp, cosTheta, g, gBack, backWeight, 0, 1),
               cloudInScatter(tau, tauClamp, cosTheta, g, gBack, backWeight, 1, 1),
               cloudInScatter(tau, tauClamp, cosTheta, g, gBack, backWeight, 0, 4),
               cloudInScatter(tau, tauClamp, cosTheta, g, gBack, backWeight, 1, 3)));
  // Steps from sigmaT dt = 0 (the limit) over the series range to long steps.
  float stepSigma = r2.x < 0.1 ? 0.0 : exp(mix(log(1e-6), log(1.0), r2.y));
  float dt = 200.0 * r2.z;
  vec3 S = vec3(r0.w, r1.w, r2.w);
  put(14, vec4(integrateStep(S, stepSigma, dt), integrateStepRiemann(S, dt).x));
  put(15, vec4(stepSigma, dt, lightMarchReach(100.0 + 2000.0 * r1.x), 0.0));
  // The schedule: n in 1..8, every step index (and one past the end).
  int n = 1 + i % 8, si = (i / 8) % (n + 1);
  float distance = 100.0 + 2000.0 * r1.x;
  put(16, vec4(lightStepStart(si, n, distance), lightStepLength(si, n, distance),
               lightLongStepDistance(distance), lightLongStepLength(distance)));

  // --- Light march: the three test densities toward a light above the horizon ---
  vec3 L = normalize(vec3(r0.x - 0.5, r0.y - 0.5, 0.1 + r0.z));
  vec3 p = vec3(100.0 * r1.x, 100.0 * r1.y, 50.0 + 500.0 * r1.z);
  gSlabTop = p.z + 5.0 * distance * L.z * r2.w;  // the slab ends somewhere along the march
  float march[3];
  for (int k = 0; k < 3; ++k) {
    gDensityKind = k;
    // The schedule of the light volume and the tests before the long step was cut at the
    // shells: split 1, the long step over [distance, 5 distance] in three parts; then a far
    // step over [5 distance, 7 distance] in two.
    LatLonLine line = LatLonLine(p, L, vec2(0.0), vec2(0.0));
    float reach = lightMarchReach(distance);
    march[k] = lightMarchDensity(CloudLightPath(p, L, line, 0.0, 0.5, distance, n, 1, n, reach,
                                                3, reach + 2.0 * distance, 2));
  }
  put(17, vec4(march[0], march[1], march[2], gSlabTop));
  // Split where the path leaves the first cloud (lightMarchDepth): the slab, then the gapped one.
  vec4 split;
  gCloudBase = gSlabTop + 2.0 * distance * L.z;
  for (int k = 2; k < 4; ++k) {
    gDensityKind = k;
    LatLonLine line = LatLonLine(p, L, vec2(0.0), vec2(0.0));
    float reach = lightMarchReach(distance);
    CloudLightDepth d = lightMarchDepth(CloudLightPath(p, L, line, 0.0, 0.5, distance, n, 1, n,
                                                       reach, 3, reach + 2.0 * distance, 2));
    split[2 * (k - 2)] = d.own;
    split[2 * (k - 2) + 1] = d.beyond;
  }
  put(24, split);
  put(18, vec4(L, distance));
  put(19, vec4(p, float(n)));

  // --- Energy: a homogeneous medium (albedo 1, unit light, so S = sigmaT) marched over 200 m
  // in 1..32 steps; in-scattered light plus transmittance must be 1.
  int steps = 1 + i % 32;
  float mediumSigma = 0.002 + 0.05 * r2.w;
  float h = 200.0 / float(steps);
  float Le = 0.0, Lr = 0.0, T = 1.0;
  for (int k = 0; k < steps; ++k) {
    Le += T * integrateStep(vec3(mediumSigma), mediumSigma, h).x;
    Lr += T * integrateStepRiemann(vec3(mediumSigma), h).x;
    T *= beerLambert(mediumSigma, h);
  }
  put(20, vec4(Le + T, Lr + T, T, mediumSigma * h));

  // --- Diffusion and boundaries: tau 0..100, g -0.5..0.9, strength 0..3, densities
  // -0.1..1.2, k 1..9, types -0.1..1.1 ---
  float tauD = 100.0 * r2.x * r2.x, gD = -0.5 + 1.4 * r1.y, strength = 3.0 * r1.z;
  float dEdge = -0.1 + 1.3 * r2.y, kEdge = 1.0 + 8.0 * r0.z, typeD = -0.1 + 1.2 * r0.y;
  put(21, vec4(diffuseTransmittance(tauD, gD), cloudDiffuseInScatter(tauD, gD, strength),
               cloudEdgeDensity(dEdge, kEdge), cloudDiffusionLeak(typeD)));
  put(22, vec4(cloudAmbientDiffuse(r0.xyz, r0.zxy * r1.w, r1.xyz, r1.zxy * (1.0 - r1.w), sigmaT,
                                   2000.0 * r2.w, 2000.0 * r0.w, 10.0 * r2.x, gD, 1.5 * r2.z),
               cloudTypeTexture(typeD)));
  put(23, vec4(cloudRollWeight(0, typeD), cloudRollWeight(1, typeD),
               cloudPhaseSkyLight(r0.xyz - 0.5, 10.0 * r2.x, r1.w).x,
               cloudFarExtinction(0.02 * r1.x, 1.1 * r2.y, 50.0 + 1000.0 * r0.w)));

  // --- Cumulus: blobs and size fields over [0, 1] and [-0.6, 0.6] (every population wins
  // somewhere, and the selector saturates at both ends), weights 0..1 with both ends held ---
  vec4 cuShape = cumulusShape(shape, vec4(r1.zw, r2.xy), vec4(r2.zw, r0.xy), 0.3 + 0.4 * r1.y,
                              r2.w);
  put(25, vec4(cloudCumulusWeight(typeD), cumulusOutline(r0.x, r0.z, r1.x, 1.2 * r1.y - 0.6),
               cuShape.r, cuShape.g));
  float wCu = clamp(1.4 * r1.w - 0.2, 0.0, 1.0);
  put(26, vec4(cumulusGD(ph, cmc, wCu), cumulusNDmod(ndfbm, cmc, ph, wCu),
               cumulusCloudDensity(shape, detail, ph, cmc, threshold, wCu), wCu));

  // --- The cloud behind a lit face: depths toward the light 0..100, behind it 0..100, the
  // faces (either depth 0) and a cloud that goes on past the probe ---
  float tauB = 100.0 * r0.x * r0.x;
  put(27, vec4(diffuseBehindShare(tauD, tauB, gD), diffuseBehindShare(0.0, tauB, gD),
               diffuseBehindShare(tauD, 0.0, gD), diffuseBehindShare(0.0, 1.0e6, gD)));
}
