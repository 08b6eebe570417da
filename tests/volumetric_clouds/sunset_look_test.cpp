// A sky at low sun as a viewer sees it on the display (issue 46): the colour of sunset-lit
// clouds and the brightness of sunset and twilight frames, at takram's view (35 N 139 E, 10 m
// up, heading 0, 60 degrees, cover 0.4 in 750-2200 m, the physical sky) and at the default
// scene's Zurich dusk. Each check reads the display image (the PNG's values before dither,
// through the default view and exposure) over the pixels above the horizon (the perception
// layers' labels), at 160 x 90.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cloud_test_util.h"
#include "engine/color/hue.h"
#include "engine/color/ocio_output.h"
#include "engine/render/exposure.h"
#include "engine/render/render_files.h"
#include "shaders/common/cloud_perception_shared.h"

namespace sky {
namespace {

class SunsetLookTest : public test::CloudRenderTest {};

// takram's view with the sun placed by hand, as issue 46 measured it.
Scene peerAtLowSun(double sunElevation, double sunAzimuth, double pitch,
                   std::vector<std::string> more = {}) {
  std::vector<std::string> o = {"output.width=160", "output.height=90", "output.perception=true",
                                "weather.spread=0", "high_clouds.cover=0.2",
                                "sun.elevation=" + std::to_string(sunElevation),
                                "sun.azimuth=" + std::to_string(sunAzimuth),
                                "camera.pitch=" + std::to_string(pitch)};
  o.insert(o.end(), more.begin(), more.end());
  return loadSceneFile(configDir() / "examples" / "peer_view.yaml", o);
}

// What the display shows of a frame, and where the clouds and the sky are.
struct Shown {
  std::vector<glm::dvec3> display;  // the PNG's RGB in 0..1 before dither
  std::vector<bool> above;          // the pixel is above the horizon (not labelled ground)
  std::vector<float> cloudAlpha;    // the volumetric clouds' opacity
  std::vector<double> luminance;    // scene-linear luminance of the beauty
};

Shown show(const Scene& scene, const RenderedFrame& frame) {
  static const OcioOutput ocio = OcioOutput::load();
  ExposureMeter meter;
  const std::vector<float> rgba =
      displayPixels(frame, scene, meter.expose(scene, frame, scene.time.start), ocio);
  const ImageLayer& beauty = frame.image.layers.at(0);
  const ImageLayer* clouds = frame.image.find("clouds");
  // The labels are the perception layers' unnamed integer layer (EXR "label.*").
  const ImageLayer* label = nullptr;
  for (const ImageLayer& l : frame.image.layers)
    if (l.integer && l.name.empty()) label = &l;
  if (!clouds || !label) {
    ADD_FAILURE() << "the frame has no clouds or label layer";
    return {};
  }
  Shown s;
  const size_t n = size_t(frame.image.width) * size_t(frame.image.height);
  for (size_t i = 0; i < n; ++i) {
    s.display.emplace_back(rgba[i * 4], rgba[i * 4 + 1], rgba[i * 4 + 2]);
    s.above.push_back(label->pixels[i * label->channels.size()] != PERCEPTION_LABEL_GROUND);
    s.cloudAlpha.push_back(clouds->pixels[i * clouds->channels.size() + 3]);
    const float* p = &beauty.pixels[i * beauty.channels.size()];
    s.luminance.push_back(0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]);
  }
  return s;
}

// The mean display value over the pixels above the horizon.
double meanAbove(const Shown& s) {
  double sum = 0.0;
  int n = 0;
  for (size_t i = 0; i < s.display.size(); ++i)
    if (s.above[i]) {
      sum += (s.display[i].r + s.display[i].g + s.display[i].b) / 3.0;
      ++n;
    }
  return n ? sum / n : 0.0;
}

// The HSV hue of the mean display colour of the lit clouds: the brightest quarter (by
// scene luminance) of the opaque cloud pixels above the horizon.
double litCloudHue(const Shown& s) {
  std::vector<size_t> opaque;
  for (size_t i = 0; i < s.display.size(); ++i)
    if (s.above[i] && s.cloudAlpha[i] > 0.95f) opaque.push_back(i);
  EXPECT_GT(opaque.size(), 200u) << "the view shows clouds";
  std::sort(opaque.begin(), opaque.end(),
            [&](size_t a, size_t b) { return s.luminance[a] > s.luminance[b]; });
  glm::dvec3 mean(0.0);
  const size_t lit = std::max<size_t>(1, opaque.size() / 4);
  for (size_t k = 0; k < lit; ++k) mean += s.display[opaque[k]];
  return hsvHueDeg(mean / double(lit));
}

TEST_F(SunsetLookTest, CloudsLitByASettingSunAreOrangeNotOchre) {
  // The sun 3 degrees up behind the camera. Issue 46 measured the lit clouds' display hue at
  // 38 degrees (yellow-ochre; takram's 13-20, photographs salmon to orange). The light's
  // colour (the sun's own spectrum, a typical day's haze, the redder light that reaches the
  // lower parts of the layer) and a view that keeps hue (AgX) brought it to 32.6 at 160 x 90
  // (33.6 through the ACES 1.0 view). The measured far field and the light beyond a sample's
  // own cloud as a beam (docs/cloud-model.md, "The light beyond a cloud's own") bring it to
  // 30.3 (31.7). The sky that other clouds hide (docs/cloud-model.md, "The sky that other
  // clouds hide": the faces toward the sun no longer take the whole glow around it) brings it
  // to 29.6 (30.7), inside the goal of 30. The cumulus shapes (docs/cloud-model.md,
  // "Cumulus shapes": many small clouds, more of them lit in part through the far field) take
  // it back to 30.5 (31.9): orange, the goal not quite met, not yet takram's salmon; Cycles'
  // lit clouds on this view are 24.0 degrees in linear light, ours 22.9 (FieldLook). Through
  // this view at our exposure, though, Cycles' show 28.3 degrees on the field and ours 29.6:
  // ours are 23 % brighter there, and AgX takes brighter orange further toward yellow
  // (docs/cloud-model.md, "How much of the 3 degree behind error is Cycles' own noise").
  // The light march's long step in 125 m parts, not 400 m (docs/cloud-model.md, "The long
  // step's parts"), took off the partly shadowed clouds the sunlight that 400 m parts let
  // through the small clouds they stepped over: the view's lit quarter 9 % darker, with less
  // of the low sun's own red-orange in it beside the sky's yellower light, and 30.8 (32.1)
  // here, 30.7 at 640x360: the light nearer Cycles', the display's hue a little further from
  // the goal. Tolerance: 31.3, half a degree over today's; and the ACES view no less yellow
  // than AgX's.
  const Scene scene = peerAtLowSun(3.0, 180.0, 10.0);
  const RenderedFrame frame = render(scene);
  const double agx = litCloudHue(show(scene, frame));
  Scene aces = scene;
  aces.output.view = "ACES 1.0 - SDR Video";
  const double acesHue = litCloudHue(show(aces, frame));
  std::printf("sun 3 deg behind: lit clouds' display hue %.1f (AgX), %.1f (ACES 1.0)\n", agx,
              acesHue);
  EXPECT_LE(agx, 31.3);
  EXPECT_GT(agx, 10.0) << "orange, not red or magenta";
  EXPECT_GE(acesHue, agx) << "the view keeps the hue that ACES skews toward yellow";
}

TEST_F(SunsetLookTest, SunsetAndTwilightFramesShowAtMidGrey) {
  // A camera or an adapted eye shows a sunset at mid-grey, not as a murky brown frame
  // (issue 46: 0.14 at the Zurich dusk before; takram's sunsets 0.42). The mean display value
  // above the horizon of takram's view with the sun 3 degrees ahead and behind, and of the
  // default scene (the Kozlov sky) looking away from the sun 0.5 degrees up and in civil
  // twilight, the sun 3.5 degrees down. Tolerance: issue 46's 0.3-0.5 for takram's physical
  // sky; 0.3-0.6 for the Kozlov sky, whose authored sunset is brighter than the physical one
  // and which the predicted exposure does not meter (docs/outputs.md, "Exposure"); and up to
  // 0.55 for the frame with the sun in it, whose glow fills its middle (0.50 here).
  struct Case {
    const char* name;
    Scene scene;
    double lo, hi;
  };
  const std::vector<std::string> zurich = {"output.width=160", "output.height=90",
                                           "output.perception=true", "camera.heading=112"};
  auto at = [&](const char* time) {
    std::vector<std::string> o = zurich;
    o.push_back(std::string("time=") + time);
    return loadSceneFile(configDir() / "default.yaml", o);
  };
  const Case cases[] = {
      {"takram's view, sun 3 deg ahead", peerAtLowSun(3.0, 0.0, 10.0), 0.3, 0.55},
      {"takram's view, sun 3 deg behind", peerAtLowSun(3.0, 180.0, 10.0), 0.3, 0.5},
      {"Zurich, sun 0.5 deg up behind", at("2024-06-21T21:20:00+02:00"), 0.3, 0.6},
      {"Zurich, civil twilight", at("2024-06-21T21:50:00+02:00"), 0.3, 0.6},
  };
  for (const Case& c : cases) {
    const double m = meanAbove(show(c.scene, render(c.scene)));
    std::printf("%s: mean display above the horizon %.3f\n", c.name, m);
    EXPECT_GE(m, c.lo) << c.name;
    EXPECT_LE(m, c.hi) << c.name;
  }
}

}  // namespace
}  // namespace sky
