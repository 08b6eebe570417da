#version 460
// The clouds' ground truth per pixel (passes/cloud_perception, docs/outputs.md "Perception
// layers"): the optical depth of the volumetric clouds along the pixel's centre ray, the
// distance at which it passes CLOUD_PERCEPTION_HIT_TAU, and the layer and type there. It
// marches the very field the raymarch does (cloud_field.glsl, the same parameters and
// textures) at full detail, as the library's queries read it, its density alone: no light, no jitter (a sample's value is the same in
// every run and every shard), no temporal reuse and no early exit, so the optical depth is
// the whole ray's, however opaque.
#include "common/volumetric_clouds_shared.h"
#include "common/cloud_perception_shared.h"
#include "common/view.glsl"
#include "common/geo.glsl"
#include "common/cloud_density.glsl"
#include "common/cloud_field.glsl"
#include "common/cloud_shells.glsl"

layout(local_size_x = VOLUMETRIC_CLOUDS_GROUP_X, local_size_y = VOLUMETRIC_CLOUDS_GROUP_Y) in;

layout(binding = CLOUD_PERCEPTION_BINDING_HIT, rgba32f) uniform writeonly image2D hitImage;

void main() {
  ivec2 id = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(id, imageSize(hitImage)))) return;
  vec3 d = viewDirection(params.view, vec2(id) + 0.5);
  float tau = 0.0;
  float hitT = 1.0 / 0.0;  // +inf: no hit
  float hitLayer = -1.0, hitType = 0.0;
  int samples = 0;
  vec2 iv[2];
  int n = params.anyCover > 0.0
              ? cloudShellIntervals(params.geo.origin.w, params.geo.origin.z, d.z,
                                    params.shellBaseM, params.shellTopM, iv)
              : 0;
  for (int k = 0; k < n; ++k) {
    float t = iv[k].x;
    float limit = 1e30;  // the longest step the density of the sample before allows
    while (t < iv[k].y && samples < CLOUD_PERCEPTION_MAX_STEPS) {
      // Lu's step, growing with distance, no longer than CLOUD_PERCEPTION_STEP_TAU optical
      // depths at the density of the sample before.
      float dt = min(min(params.stepM + params.stepGrowth * t, limit), iv[k].y - t);
      vec3 p = d * (t + 0.5 * dt);
      CloudSample s;
      ++samples;
      // At full detail (a footprint of 0), as the queries' field and the density export read
      // it: the truth along the centre ray, not a pixel's blurred mean.
      if (!cloudSampleAtLla(p, latLonAltitude(params.geo, p), 0.0, true, CLOUD_NOISE_ALL, s)) {
        // Nothing to sample here (outside the region, between the layers, far from cover):
        // the coarse map is dilated by kilometres, so a double step cannot jump a cloud.
        limit = 1e30;
        t += 2.0 * dt;
        continue;
      }
      float sigma = params.extinction * s.density;
      if (sigma > 0.0) {
        // Until the hit, steps of CLOUD_PERCEPTION_STEP_TAU place it; past it only the sum
        // is left to take, and Lu's step samples the density as finely as the lit march
        // does: deep inside a cumulus the fine steps cost five times the lit march.
        float stepLimit = tau < CLOUD_PERCEPTION_HIT_TAU ? max(CLOUD_PERCEPTION_STEP_TAU / sigma, 2.0)
                                                         : 1e29;
        if (dt > 1.01 * stepLimit && limit >= 1e29 && tau < CLOUD_PERCEPTION_HIT_TAU) {
          // Entering a cloud with a step too deep for it: take it again at the finer step,
          // so the hit is not placed a whole coarse step late.
          limit = stepLimit;
          continue;
        }
        limit = stepLimit;
        float stepTau = sigma * dt;
        if (tau < CLOUD_PERCEPTION_HIT_TAU && tau + stepTau >= CLOUD_PERCEPTION_HIT_TAU) {
          // Homogeneous within the step: the depth rises linearly.
          hitT = t + (CLOUD_PERCEPTION_HIT_TAU - tau) / sigma;
          hitLayer = float(s.layer);
          hitType = s.type;
        }
        tau += stepTau;
      } else {
        limit = 1e30;
      }
      t += dt;
    }
  }
  imageStore(hitImage, id, vec4(tau, hitT, hitLayer, hitType));
}
