#version 460
// Temporal reuse of the volumetric clouds (passes/cloud_temporal; docs/clouds.md, "Temporal
// reuse"), after Schneider's Nubis (2015, 2017): each frame the cloud pass marches one pixel
// of every block x block square, a different one each frame, and this pass builds the
// full-size clouds from that and from last frame's:
//  - a pixel marched this frame takes its new value;
//  - any other takes last frame's clouds where its cloud was then: the point at its depth,
//    moved back by the wind's drift, seen from last frame's camera (Catmull-Rom, so sixteen
//    frames of resampling do not blur the clouds' edges);
//  - where that is uncertain (the depth around it spans enough parallax to move the point by
//    over half a pixel: a disocclusion, a cloud edge crossing one further back) the history is
//    clamped into the range of this frame's four nearest marched pixels, so nothing that is
//    not there any more lingers (no ghost); where there is no history (a cut, the screen's edge) the
//    marched neighbours are upsampled, weighted by how alike their rays are (depth-aware: a
//    ray that meets the ground first never takes a cloud from one that reaches the shells).
// Every pixel is marched afresh once every block^2 frames, so whatever the reprojection
// missed is gone by then.
#include "common/cloud_temporal_shared.h"
#include "common/params_block.glsl"
#include "common/view.glsl"
#include "common/cloud_shells.glsl"

layout(local_size_x = CLOUD_TEMPORAL_GROUP_X, local_size_y = CLOUD_TEMPORAL_GROUP_Y) in;

layout(std140, binding = CLOUD_TEMPORAL_BINDING_PARAMS) uniform CloudTemporalBlock {
  CloudTemporalParams paramsBlock[1];
};
#define params paramsBlock[SKY_PARAMS_INDEX]
layout(binding = CLOUD_TEMPORAL_BINDING_MARCHED, rgba32f) uniform readonly image2D marched;
layout(binding = CLOUD_TEMPORAL_BINDING_MARCHED_DEPTH, rg32f) uniform readonly image2D marchedDepth;
layout(binding = CLOUD_TEMPORAL_BINDING_HISTORY) uniform sampler2D history;
layout(binding = CLOUD_TEMPORAL_BINDING_HISTORY_DEPTH, rg32f) uniform readonly image2D historyDepth;
layout(binding = CLOUD_TEMPORAL_BINDING_CLOUDS, rgba32f) uniform writeonly image2D outClouds;
layout(binding = CLOUD_TEMPORAL_BINDING_DEPTH, rg32f) uniform writeonly image2D outDepth;

// Where a ray with no cloud on it is taken to be, when nothing better is known (m): far
// enough that only the camera's turning moves it.
#define CLOUD_TEMPORAL_FAR_M 1.0e6
// The parallax (pixels) between the nearest and the farthest depth around a pixel above which
// its history is clamped into the marched neighbours' range.
#define CLOUD_TEMPORAL_PARALLAX_PX 0.5

// The view pixel whose march texel q of this frame holds (a square cut by the image's edge
// marches its nearest pixel, as the cloud pass does).
ivec2 marchedPixel(ivec2 q) {
  return min(q * int(params.block) + ivec2(params.offsetX, params.offsetY),
             ivec2(params.view.size.xy) - 1);
}

// The continuous pixel of last frame's view that saw the cloud point now at distance `dist`
// along this frame's ray d; false when that view did not see it.
bool previousPixel(vec3 d, float dist, out vec2 pixel) {
  vec3 x = d * dist - params.windShift.xyz - params.previousPosition.xyz;
  vec3 v = vec3(dot(params.toPreviousX.xyz, x), dot(params.toPreviousY.xyz, x),
                dot(params.toPreviousZ.xyz, x));
  if (!viewPixel(params.previousView, normalize(v), pixel)) return false;
  vec2 size = vec2(params.previousView.size.xy);
  return all(greaterThanEqual(pixel, vec2(0.0))) && all(lessThanEqual(pixel, size));
}

// Last frame's clouds at a continuous pixel: Catmull-Rom from five bilinear taps (the four
// corner taps, which weigh least, left out and the rest renormalised), clamped to the four
// nearest texels so the spline's overshoot cannot build up frame after frame.
vec4 sampleHistory(vec2 pixel) {
  vec2 size = vec2(textureSize(history, 0));
  vec2 p1 = floor(pixel - 0.5) + 0.5;
  vec2 f = pixel - p1;
  vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
  vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
  vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
  vec2 w3 = f * f * (-0.5 + 0.5 * f);
  vec2 w12 = w1 + w2;
  vec2 p12 = (p1 + w2 / w12) / size;
  vec2 p0 = (p1 - 1.0) / size;
  vec2 p3 = (p1 + 2.0) / size;
  vec4 sum = textureLod(history, vec2(p12.x, p0.y), 0.0) * (w12.x * w0.y) +
             textureLod(history, vec2(p0.x, p12.y), 0.0) * (w0.x * w12.y) +
             textureLod(history, p12, 0.0) * (w12.x * w12.y) +
             textureLod(history, vec2(p3.x, p12.y), 0.0) * (w3.x * w12.y) +
             textureLod(history, vec2(p12.x, p3.y), 0.0) * (w12.x * w3.y);
  float weight = w12.x * w0.y + w0.x * w12.y + w12.x * w12.y + w3.x * w12.y + w12.x * w3.y;
  vec4 c = sum / weight;
  ivec2 t = ivec2(floor(pixel - 0.5));
  ivec2 hi = ivec2(size) - 1;
  vec4 a = texelFetch(history, clamp(t, ivec2(0), hi), 0);
  vec4 b = texelFetch(history, clamp(t + ivec2(1, 0), ivec2(0), hi), 0);
  vec4 e = texelFetch(history, clamp(t + ivec2(0, 1), ivec2(0), hi), 0);
  vec4 g = texelFetch(history, clamp(t + ivec2(1, 1), ivec2(0), hi), 0);
  return clamp(c, min(min(a, b), min(e, g)), max(max(a, b), max(e, g)));
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(params.view.size.xy)))) return;
  ivec2 marchedSize = imageSize(marched);
  ivec2 q = p / int(params.block);
  vec4 clouds;
  float depth;
  float entry;  // where this pixel's ray reaches the shells (-1: never), kept with the depth
  if (all(equal(p, marchedPixel(q)))) {
    // Marched this frame.
    clouds = imageLoad(marched, q);
    vec2 z = imageLoad(marchedDepth, q).rg;
    depth = z.r;
    entry = z.g;
  } else {
    vec3 d = viewDirection(params.view, vec2(p) + 0.5);
    entry = cloudShellEntry(params.planetRadiusM, params.cameraAltitudeM, params.shellBaseM,
                            params.shellTopM, d);
    // This frame's four marched neighbours around the pixel: a depth-aware bilinear
    // upsampling of them, their range (the clamp) and their nearest and farthest cloud.
    vec2 f = (vec2(p) - vec2(params.offsetX, params.offsetY)) / float(params.block);
    ivec2 q0 = ivec2(floor(f));
    vec2 t = f - vec2(q0);
    vec4 sum = vec4(0.0);
    float depthSum = 0.0, depthWeight = 0.0, weightSum = 0.0;
    vec4 lo = vec4(1e30), hi = vec4(-1e30);
    float near = 1e30, far = 0.0;
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        ivec2 qi = clamp(q0 + ivec2(i, j), ivec2(0), marchedSize - 1);
        float w = (i == 0 ? 1.0 - t.x : t.x) * (j == 0 ? 1.0 - t.y : t.y);
        vec4 c = imageLoad(marched, qi);
        vec2 z = imageLoad(marchedDepth, qi).rg;  // depth, where its ray reached the shells
        // Rays that both miss the shells, or both reach them at similar distances, agree.
        w = max(w, 1e-4) * cloudShellAlike(z.g, entry);
        sum += w * c;
        weightSum += w;
        // The depth of the cloudy ones alone, by opacity: a clear neighbour has no depth (0),
        // and averaging it in would pull the point toward the camera.
        depthSum += w * c.a * z.r;
        depthWeight += w * c.a;
        lo = min(lo, c);
        hi = max(hi, c);
        if (z.r > 0.0) {
          near = min(near, z.r);
          far = max(far, z.r);
        }
      }
    vec4 upsampled = sum / weightSum;
    float upsampledDepth = depthWeight > 0.0 ? depthSum / depthWeight : 0.0;
    // Where no cloud is near, the point is taken where the ray meets the shells, or far.
    float clear = entry > 0.0 ? entry : CLOUD_TEMPORAL_FAR_M;
    if (far <= 0.0) near = far = clear;
    float guess = upsampledDepth > 0.0 ? upsampledDepth : clear;
    clouds = upsampled;
    depth = upsampledDepth;
    vec2 prev;
    if (params.historyValid != 0u && previousPixel(d, guess, prev)) {
      // The history knows this pixel's own depth better than the sparse neighbours do: look
      // again from where the guess led (a fixed-point step).
      float known = imageLoad(historyDepth, clamp(ivec2(prev), ivec2(0),
                                                  ivec2(params.previousView.size.xy) - 1)).r;
      vec2 refined;
      if (known > 0.0 && previousPixel(d, known, refined)) {
        prev = refined;
        guess = known;
      }
      vec4 h = sampleHistory(prev);
      // How far the point would move were it at the nearest or the farthest depth around.
      vec2 atNear, atFar;
      bool seenNear = previousPixel(d, min(near, guess), atNear);
      bool seenFar = previousPixel(d, max(far, guess), atFar);
      float parallax = seenNear && seenFar ? max(length(atNear - prev), length(atFar - prev))
                                           : 1e30;
      if (parallax > CLOUD_TEMPORAL_PARALLAX_PX) h = clamp(h, lo, hi);
      clouds = h;
      depth = imageLoad(historyDepth, clamp(ivec2(prev), ivec2(0),
                                            ivec2(params.previousView.size.xy) - 1)).r;
      if (clouds.a <= 0.0) depth = 0.0;
    }
  }
  imageStore(outClouds, p, clouds);
  imageStore(outDepth, p, vec4(depth, entry, 0.0, 0.0));
}
