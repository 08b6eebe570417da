// The march's grain on lit cloud faces (issue 46): one march per pixel against the reference
// march at the peer's pixel size, with the still's filter (clouds.denoise) and without.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cloud_test_util.h"

namespace sky {
namespace {

class CloudGrainTest : public test::CloudRenderTest {};

// The peer's view (configs/examples/peer_view.yaml: cumulus at 40 % cover, 750-2200 m) with
// overrides.
Scene peerScene(std::vector<std::string> overrides) {
  return loadSceneFile(configDir() / "examples" / "peer_view.yaml", overrides);
}

// The relative high-frequency energy of the beauty's luminance over `mask`: the RMS of each
// pixel less its 3 x 3 mean, over the mean.
double highFrequency(const RenderedFrame& f, const std::vector<char>& mask) {
  const ImageLayer& beauty = f.image.layers.at(0);
  const int w = f.image.width, h = f.image.height;
  const size_t stride = beauty.channels.size();
  auto lum = [&](int x, int y) {
    x = std::clamp(x, 0, w - 1);
    y = std::clamp(y, 0, h - 1);
    return test::luminance(&beauty.pixels[(size_t(y) * size_t(w) + size_t(x)) * stride]);
  };
  double sq = 0.0, sum = 0.0;
  int n = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!mask[size_t(y) * size_t(w) + size_t(x)]) continue;
      double box = 0.0;
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) box += lum(x + i, y + j) / 9.0;
      const double hp = lum(x, y) - box;
      sq += hp * hp;
      sum += lum(x, y);
      ++n;
    }
  return n > 0 ? std::sqrt(sq / n) / (sum / n) : 0.0;
}

// The lit faces of one frame: pixels whose 3 x 3 neighbourhood is opaque in `ref` (clouds.A >
// 0.95) and brighter than the opaque pixels' median. `opaque` gets the opaque pixels.
std::vector<char> litFaces(const RenderedFrame& ref, std::vector<char>& opaque) {
  const test::CloudLayerView c(ref);
  const ImageLayer& beauty = ref.image.layers.at(0);
  const size_t stride = beauty.channels.size();
  opaque.assign(size_t(c.width()) * size_t(c.height()), 0);
  std::vector<char> lit = opaque;
  std::vector<double> values;
  for (int y = 1; y + 1 < c.height(); ++y)
    for (int x = 1; x + 1 < c.width(); ++x) {
      bool all = true;
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) all = all && c.at(x + i, y + j).alpha > 0.95f;
      const size_t k = size_t(y) * size_t(c.width()) + size_t(x);
      opaque[k] = all;
      if (all) values.push_back(test::luminance(&beauty.pixels[k * stride]));
    }
  if (values.empty()) return lit;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  const double median = values[values.size() / 2];
  for (size_t k = 0; k < opaque.size(); ++k)
    lit[k] = opaque[k] && test::luminance(&beauty.pixels[k * stride]) > median;
  return lit;
}

// The RMS of the beauty's luminance less the reference's over `mask`, over the reference's mean.
double errorAgainst(const RenderedFrame& f, const RenderedFrame& ref,
                    const std::vector<char>& mask) {
  const ImageLayer& a = f.image.layers.at(0);
  const ImageLayer& b = ref.image.layers.at(0);
  const size_t stride = a.channels.size();
  double sq = 0.0, sum = 0.0;
  int n = 0;
  for (size_t k = 0; k < mask.size(); ++k) {
    if (!mask[k]) continue;
    const double la = test::luminance(&a.pixels[k * stride]);
    const double lb = test::luminance(&b.pixels[k * stride]);
    sq += (la - lb) * (la - lb);
    sum += lb;
    ++n;
  }
  return n > 0 ? std::sqrt(sq / n) / (sum / n) : 0.0;
}

TEST_F(CloudGrainTest, LitFacesAreNoGrainierThanTheReferenceMarch) {
  // The peer's noon view at its 640 x 360 pixel size (60 / 360 degrees), two 160 x 90 parts of
  // it: turned up and right to the nearest large cumulus, and ahead to the clouds 5-15 km off
  // above the horizon, whose texture is a few pixels wide. One march per pixel leaves grain on
  // the lit faces (docs/clouds.md, "Grain"): measured, 2.56 and 1.33 times the reference
  // march's high-frequency energy; the still's filter (clouds.denoise) takes it to 0.57 and
  // 0.92 times, and each part closer to the reference (the error 4.2 -> 2.8 % and 4.7 ->
  // 3.7 %).
  struct Part {
    const char* name;
    int heading, pitch;
  };
  for (const Part& part : {Part{"nearest cloud", 27, 36}, Part{"clouds 5-15 km off", 10, 12}}) {
    const std::vector<std::string> view = {
        "output.width=160", "output.height=90", "camera.vertical_fov=15",
        "camera.heading=" + std::to_string(part.heading),
        "camera.pitch=" + std::to_string(part.pitch), "high_clouds.cover=0"};
    std::vector<std::string> reference = view, grainy = view;
    reference.push_back("clouds.quality=reference");
    grainy.push_back("clouds.denoise=false");
    const RenderedFrame ref = render(peerScene(reference));
    const RenderedFrame standard = render(peerScene(view));
    const RenderedFrame raw = render(peerScene(grainy));
    std::vector<char> opaque;
    const std::vector<char> lit = litFaces(ref, opaque);
    const int litCount = int(std::count(lit.begin(), lit.end(), 1));
    ASSERT_GT(litCount, 300) << part.name << ": the part should show lit cloud";
    const double hfRef = highFrequency(ref, lit), hfStd = highFrequency(standard, lit),
                 hfRaw = highFrequency(raw, lit);
    const double errStd = errorAgainst(standard, ref, opaque),
                 errRaw = errorAgainst(raw, ref, opaque);
    std::printf("%s, lit faces (%d px): high-frequency energy reference %.4f, standard %.4f "
                "(%.2f x), without the filter %.4f (%.2f x); error %.2f %%, without %.2f %%\n",
                part.name, litCount, hfRef, hfStd, hfStd / hfRef, hfRaw, hfRaw / hfRef,
                100.0 * errStd, 100.0 * errRaw);
    // The bar: no higher than the reference's (5 % for the reference's own grain).
    EXPECT_LE(hfStd, 1.05 * hfRef) << part.name;
    // The grain is there without the filter, and the filter brings the picture closer to the
    // reference: it takes grain, not the clouds' texture.
    EXPECT_GT(hfRaw, 1.2 * hfRef) << part.name;
    EXPECT_LT(errStd, errRaw) << part.name;
  }
}

}  // namespace
}  // namespace sky
