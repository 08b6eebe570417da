#pragma once
// The display exposure of each frame (output.exposure). The scene-linear image is physical;
// the display path multiplies it by 2^ev before the OCIO view. docs/outputs.md.
#include <optional>

#include "engine/render/renderer.h"
#include "engine/scene/iso_time.h"
#include "engine/scene/scene.h"

namespace sky {

struct FrameExposure {
  ExposureMode mode = ExposureMode::Auto;
  double ev = 0.0;  // stops applied before the view, output.exposure_ev included
  // histogram: the metered luminance (renderer units) and the exposure it asked for before
  // the sequence's adaptation; 0 otherwise.
  double meteredLuminance = 0.0;
  double targetEv = 0.0;
};

// Histogram metering: the log-average luminance of the frame's beauty over the middle of its
// luminance histogram (the darkest and the brightest 5 % left out: the sun's and the moon's
// discs, a black corner), in renderer units. 0 for an empty or black frame.
double meteredLuminance(const RenderedFrame& frame);

// The exposure histogram metering asks for at a metered luminance: 0 stops down to the
// luminance of a sunlit scene (kHistogramReference), and below it `nightAdaptation` of the
// stops it is darker, as the auto exposure's night lift; never darker than 0 stops.
double histogramEv(double meteredLuminance, double nightAdaptation);

// Exposes the frames of one render in order; for a sequence with histogram metering it
// carries the adapted exposure from frame to frame.
class ExposureMeter {
public:
  FrameExposure expose(const Scene& scene, const RenderedFrame& frame, const IsoTime& time);

private:
  std::optional<double> mLastEv;
  IsoTime mLastTime;
};

}  // namespace sky
