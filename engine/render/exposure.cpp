#include "engine/render/exposure.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/lighting/light_model.h"

namespace sky {
namespace {

// The log-average luminance of a sunlit scene (renderer units; the default scene metres 0.135
// at noon): below it the histogram exposure lifts by night_adaptation of the stops the frame
// is darker. Through dusk the exposure then follows the frame's own light, so a sequence
// cannot dip where the twilight fades before the moonlight takes over, and a moonlit night
// (metering ~5e-7) comes out 14.6 stops up: dim, about 3.5 stops below the day's display.
constexpr double kHistogramReference = 0.14;
constexpr double kHistogramClip = 0.05;  // share left out at each end of the histogram

}  // namespace

double meteredLuminance(const RenderedFrame& frame) {
  const ImageLayer* beauty = frame.image.find("");
  if (!beauty || beauty->channels.size() < 3) return 0.0;
  const size_t c = beauty->channels.size();
  std::vector<double> logs;
  logs.reserve(beauty->pixels.size() / c);
  for (size_t i = 0; i + 2 < beauty->pixels.size(); i += c) {
    const double y = light::luminance(
        glm::dvec3(beauty->pixels[i], beauty->pixels[i + 1], beauty->pixels[i + 2]));
    if (std::isfinite(y) && y > 0.0) logs.push_back(std::log2(y));
  }
  if (logs.empty()) return 0.0;
  std::sort(logs.begin(), logs.end());
  const size_t skip = static_cast<size_t>(kHistogramClip * static_cast<double>(logs.size()));
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = skip; i < logs.size() - skip; ++i, ++n) sum += logs[i];
  return n ? std::exp2(sum / static_cast<double>(n)) : 0.0;
}

double histogramEv(double metered, double nightAdaptation) {
  if (!(metered > 0.0)) return 0.0;
  return std::max(0.0, nightAdaptation * std::log2(kHistogramReference / metered));
}

FrameExposure ExposureMeter::expose(const Scene& scene, const RenderedFrame& frame,
                                    const IsoTime& time) {
  const OutputSettings& o = scene.output;
  FrameExposure e;
  e.mode = o.exposure;
  double ev = 0.0;
  switch (o.exposure) {
    case ExposureMode::Auto:
      ev = frame.lighting.autoExposureEv;
      break;
    case ExposureMode::Fixed:
      break;
    case ExposureMode::Histogram: {
      e.meteredLuminance = meteredLuminance(frame);
      e.targetEv = histogramEv(e.meteredLuminance, scene.lighting.nightAdaptation);
      ev = e.targetEv;
      // A sequence adapts toward each frame's exposure with the time constant (an eye or a
      // camera follows the light), in the scene's time.
      if (mLastEv && o.exposureAdaptationS > 0.0) {
        const double dt = std::abs(time.secondsSince(mLastTime));
        ev = e.targetEv + (*mLastEv - e.targetEv) * std::exp(-dt / o.exposureAdaptationS);
      }
      mLastEv = ev;
      mLastTime = time;
      break;
    }
  }
  e.ev = ev + o.exposureEv;
  return e;
}

}  // namespace sky
