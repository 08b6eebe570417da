// What a viewer sees of the clouds, at tiny sizes with stated tolerances (issue 14): noon
// tops brighter than the clear sky beside them, bases blue-grey rather than brown, backlit
// edges brighter than the cores, backlit cores blue-grey, a horizon band no noisier than a supersampled render of the
// same view (and the default view's within 10 % RMS of it), no horizontal striations, altostratus
// smoother than altocumulus, stratocumulus in rolls along the wind, and no periodic dither pattern.
// Each check reads the final scene-linear image (the "beauty" layer) or the clouds' own layer, as
// stated.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cloud_test_util.h"

namespace sky {
namespace {

using test::CloudLayerView;

class CloudLookTest : public test::CloudRenderTest {};

// The peer's view (configs/examples/peer_view.yaml) at a test size, with overrides.
Scene peerView(int width, int height, std::vector<std::string> overrides = {}) {
  overrides.push_back("output.width=" + std::to_string(width));
  overrides.push_back("output.height=" + std::to_string(height));
  return loadSceneFile(configDir() / "examples" / "peer_view.yaml", overrides);
}

// The final image's pixel (scene-linear RGB) and its luminance.
struct Beauty {
  explicit Beauty(const RenderedFrame& f)
      : layer(f.image.layers.at(0)), width(f.image.width), height(f.image.height) {}
  glm::vec3 rgb(int x, int y) const {
    const float* p = &layer.pixels[(static_cast<size_t>(y) * width + x) * layer.channels.size()];
    return {p[0], p[1], p[2]};
  }
  double lum(int x, int y) const {
    const glm::vec3 c = rgb(x, y);
    return test::luminance(&c.x);
  }
  const ImageLayer& layer;
  int width, height;
};

// The mean of the largest `share` of the values.
double topShare(std::vector<double> v, double share) {
  std::sort(v.begin(), v.end(), std::greater<>());
  const size_t n = std::max<size_t>(1, static_cast<size_t>(share * static_cast<double>(v.size())));
  double sum = 0.0;
  for (size_t i = 0; i < n; ++i) sum += v[i];
  return sum / static_cast<double>(n);
}

TEST_F(CloudLookTest, NoonTopsAreBrighterThanTheClearSkyBesideThem) {
  // The peer's view: sun 60 degrees up behind the camera, cumulus ahead. The sunlit clouds'
  // brightest tenth against the clear sky in the same rows (above the horizon band). A real
  // sunlit cumulus is 2-4 times the blue sky's luminance; the old model's grey clouds were
  // about as bright as the sky.
  const RenderedFrame f = render(peerView(96, 54));
  const Beauty b(f);
  const CloudLayerView c(f);
  std::vector<double> cloud, sky;
  for (int y = 0; y < b.height / 2; ++y)
    for (int x = 0; x < b.width; ++x) {
      const float a = c.at(x, y).alpha;
      if (a > 0.95f) cloud.push_back(b.lum(x, y));
      if (a < 0.02f) sky.push_back(b.lum(x, y));
    }
  ASSERT_GT(cloud.size(), 50u) << "the view holds clouds";
  ASSERT_GT(sky.size(), 50u) << "and clear sky";
  double skyMean = 0.0;
  for (double v : sky) skyMean += v;
  skyMean /= static_cast<double>(sky.size());
  const double tops = topShare(cloud, 0.1);
  std::cout << "noon: brightest cloud tenth " << tops << ", clear sky " << skyMean << "\n";
  EXPECT_GT(tops, 1.5 * skyMean);
}

TEST_F(CloudLookTest, BasesAreGreyNotBrown) {
  // Looking up at the bases of noon cumulus (60 % cover) 90 degrees from the sun (sun 60
  // degrees up in the south, the view 30 degrees up to the north), so no forward-scattered
  // sunlight brightens them. The darkest third of the opaque cloud pixels, as the viewer
  // sees them: lit by the sky, the ground and sunlight diffused through the cloud, they must
  // be grey, not brown: red less blue under 8 % of their luminance, and the chroma (largest
  // less smallest channel) under 15 %. Measured: 5 % (0.45, 0.44, 0.43); the papers' lighting
  // (no diffusion term, extinction 0.04) gives 10 % at half the luminance, and with the old
  // ground-coloured ambient more. The blue of distant bases comes with the aerial
  // perspective between them and the eye, which the clouds do not have yet.
  const RenderedFrame f = render(
      peerView(96, 54, {"camera.pitch=30", "camera.vertical_fov=40", "weather.cover_low=0.6"}));
  const Beauty b(f);
  const CloudLayerView c(f);
  struct Px {
    double lum;
    glm::vec3 rgb;
  };
  std::vector<Px> opaque;
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x)
      if (c.at(x, y).alpha > 0.98f) opaque.push_back({b.lum(x, y), b.rgb(x, y)});
  ASSERT_GT(opaque.size(), 200u) << "the view is mostly cloud";
  std::sort(opaque.begin(), opaque.end(), [](const Px& p, const Px& q) { return p.lum < q.lum; });
  glm::dvec3 sum(0.0);
  double lum = 0.0;
  const size_t n = opaque.size() / 3;
  for (size_t i = 0; i < n; ++i) {
    sum += glm::dvec3(opaque[i].rgb);
    lum += opaque[i].lum;
  }
  sum /= static_cast<double>(n);
  lum /= static_cast<double>(n);
  const double warm = (sum.r - sum.b) / lum;
  const double chroma = (std::max({sum.r, sum.g, sum.b}) - std::min({sum.r, sum.g, sum.b})) / lum;
  std::cout << "bases: rgb " << sum.r << " " << sum.g << " " << sum.b << ", (r - b) / L " << warm
            << ", chroma / L " << chroma << "\n";
  EXPECT_LT(warm, 0.08) << "bases lean to brown";
  EXPECT_LT(chroma, 0.15) << "bases are not grey";
}

TEST_F(CloudLookTest, BacklitEdgesGlowBrighterThanTheCores) {
  // The sun 10 degrees up straight ahead, behind the clouds: the thin edges (opacity 0.2-0.7)
  // forward-scatter the sun toward the eye (the silver lining) and must outshine the opaque
  // cores (opacity > 0.98), each taken as the clouds' own radiance (premultiplied colour /
  // opacity, the sky behind left out), by at least a half.
  const RenderedFrame f = render(peerView(
      96, 54, {"sun.azimuth=0", "sun.elevation=10", "camera.pitch=12", "weather.cover_low=0.3"}));
  const CloudLayerView c(f);
  double edges = 0.0, cores = 0.0;
  int edgeCount = 0, coreCount = 0;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x) {
      const test::CloudPixel p = c.at(x, y);
      if (p.alpha <= 0.0f) continue;
      const glm::vec3 own = p.rgb / p.alpha;
      const double l = test::luminance(&own.x);
      if (p.alpha > 0.2f && p.alpha < 0.7f) {
        edges += l;
        ++edgeCount;
      } else if (p.alpha > 0.98f) {
        cores += l;
        ++coreCount;
      }
    }
  ASSERT_GT(edgeCount, 20);
  ASSERT_GT(coreCount, 20);
  edges /= edgeCount;
  cores /= coreCount;
  std::cout << "backlit: edges " << edges << " (" << edgeCount << " px), cores " << cores << " ("
            << coreCount << " px)\n";
  EXPECT_GT(edges, 1.5 * cores);
}

// The blue/red ratio of the darker half (by luminance) of the opaque cloud pixels (opacity
// above 0.9) of a path-traced scene (configs/pathtrace/, docs/cloud-model.md), from the clouds'
// own layer, as scripts/pathtrace/compare.py reports it for the core.
double coreBlueRed(const RenderedFrame& f) {
  const CloudLayerView c(f);
  std::vector<test::CloudPixel> opaque;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x)
      if (c.at(x, y).alpha > 0.9f) opaque.push_back(c.at(x, y));
  EXPECT_GT(opaque.size(), 100u) << "the cloud fills a good part of the view";
  std::sort(opaque.begin(), opaque.end(), [](const test::CloudPixel& p, const test::CloudPixel& q) {
    return test::luminance(&p.rgb.x) < test::luminance(&q.rgb.x);
  });
  double red = 0.0, blue = 0.0;
  for (size_t i = 0; i < opaque.size() / 2; ++i) {
    red += opaque[i].rgb.r;
    blue += opaque[i].rgb.b;
  }
  return red > 0.0 ? blue / red : 0.0;
}

TEST_F(CloudLookTest, BacklitCoresAreBlueGreyAndNoonCoresGrey) {
  // Issue 30: the shadowed half of a cumulus lit from behind by a low sun takes most of its
  // light from the sky (97 % in Cycles at 12 degrees), so it is blue-grey, not the tan of
  // sunlight diffused through it: blue/red at least 0.8 with the sun 3 and 12 degrees up
  // behind the cloud, in both sky models, and at least 0.95 at noon. Measured here 0.93, 1.36,
  // 1.23 and 0.98 (Cycles 1.15-1.65 and 1.05); a beige cast measured 0.54 backlit before.
  // Issue 46 gave the sun its own colour, (1.09, 0.97, 0.93) above the air, in place of
  // white: Cycles lit by that sun puts the noon core at 0.92 (scripts/pathtrace/compare.sh
  // cumulus_side_noon, 160x90, 128 samples), ours at 0.83, so noon asks at least 0.8. The
  // sky, that sun's light, is warmer too: with the sun 3 degrees up Cycles' core is 1.04
  // (ours 0.77), so backlit asks at least 0.72, the same share of Cycles' as before.
  struct Case {
    const char* scene;
    double atLeast;
  };
  for (const Case c : {Case{"cumulus_sun12_toward", 0.72}, Case{"cumulus_sun3_toward", 0.72},
                       Case{"cumulus_sun12_toward_kozlov", 0.72}, Case{"cumulus_side_noon", 0.8}}) {
    const RenderedFrame f = render(loadSceneFile(configDir() / "pathtrace" / (std::string(c.scene) + ".yaml"),
                                                 {"output.width=160", "output.height=90"}));
    const double br = coreBlueRed(f);
    std::cout << c.scene << ": core blue/red " << br << "\n";
    EXPECT_GE(br, c.atLeast) << c.scene;
  }
}

TEST_F(CloudLookTest, ASideLitCumulusDarkensTowardItsBase) {
  // Issue 30: seen from the side with the sun 3 degrees up behind the camera, Cycles draws the
  // cumulus bright in its middle and dark at its base, where the diffuse light escapes
  // through the boundary (docs/cloud-model.md, "The diffuse field at the boundaries"). The
  // mean luminance of the cloud's bottom quarter of rows over that of the rows from 25 % to
  // 60 % down: Cycles 0.27 (at 320x180); here 0.40 with the boundary share, 0.47 without it at
  // the same strength and 0.49 before (strength 1.4), when the diffusion lit the face evenly
  // and the base twice too bright (30.8 % off Cycles).
  const RenderedFrame f =
      render(loadSceneFile(configDir() / "pathtrace" / "cumulus_sun3_away.yaml",
                           {"output.width=160", "output.height=90"}));
  const CloudLayerView c(f);
  int top = c.height(), bottom = -1;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x)
      if (c.at(x, y).alpha > 0.5f) top = std::min(top, y), bottom = std::max(bottom, y);
  ASSERT_GT(bottom - top, 15) << "the cloud spans a good part of the view";
  const int h = bottom - top + 1;
  auto rowsMean = [&](int from, int to) {
    double sum = 0.0;
    int n = 0;
    for (int y = top + from; y < top + to; ++y)
      for (int x = 0; x < c.width(); ++x)
        if (const test::CloudPixel p = c.at(x, y); p.alpha > 0.5f)
          sum += test::luminance(&p.rgb.x), ++n;
    return n > 0 ? sum / n : 0.0;
  };
  const double base = rowsMean(int(0.75 * h), h), middle = rowsMean(int(0.25 * h), int(0.6 * h));
  std::cout << "side-lit cumulus: base " << base << ", middle " << middle << "\n";
  ASSERT_GT(middle, 0.0);
  EXPECT_LT(base / middle, 0.43);
}

TEST_F(CloudLookTest, ADecksBaseOverheadIsAsBrightAsThePathTracersBase) {
  // Issue 30: looking up into a stratocumulus deck's base under a high sun, what comes out
  // through the base is the diffuse light going out, brightest straight overhead (the
  // two-stream solution's I0 (1 + 3/2 mu), docs/cloud-model.md). Cycles puts the cloud pixels
  // of the top 13 % of rows (75-80 degrees up) at a mean luminance of 2.60 in the renderer's
  // units (320x180, 256 samples, lit with our own sun and sky); here 2.34 at 160x90, 2.02
  // when each boundary's share went only to 1 (28.1 % off Cycles over the deck, 24.0 % now).
  // Issue 46 changed the light (the sun's own colour, turbidity 0.15 for 0.1): Cycles lit by
  // it puts those pixels at 2.41 (160x90, 128 samples), ours at 2.20. Tolerance: 15 %.
  const RenderedFrame f =
      render(loadSceneFile(configDir() / "pathtrace" / "stratocumulus_below.yaml",
                           {"output.width=160", "output.height=90"}));
  const CloudLayerView c(f);
  double sum = 0.0;
  int n = 0;
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < c.width(); ++x)
      if (const test::CloudPixel p = c.at(x, y); p.alpha > 0.5f)
        sum += test::luminance(&p.rgb.x), ++n;
  ASSERT_GT(n, c.width() * 6) << "the deck fills the top of the view";
  const double cycles = 2.41;
  std::cout << "deck base overhead: " << sum / n << " (Cycles " << cycles << ")\n";
  EXPECT_NEAR(sum / n / cycles, 1.0, 0.15);
}

// The mean squared difference of horizontally adjacent luminances over rows [y0, y1): the
// pixel-to-pixel variation a viewer sees as speckle.
double adjacentVariance(const std::vector<double>& lum, int width, int y0, int y1) {
  double sum = 0.0;
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x + 1 < width; ++x) {
      const double d =
          lum[static_cast<size_t>(y) * width + x + 1] - lum[static_cast<size_t>(y) * width + x];
      sum += d * d;
      ++n;
    }
  return sum / n;
}

TEST_F(CloudLookTest, TheHorizonBandIsNoNoisierThanASupersampledRender) {
  // Pitch 5: the horizon sits low in the frame and the band just above it looks through
  // 100+ km of the low layer. The render at 96 x 54 against the same view at 384 x 216 box
  // filtered to 96 x 54 (16 rays a pixel): a renderer that filters by footprint gives what the
  // supersampled one averages to, row by row, and little of the speckle of clouds hit or
  // missed at random. Measured (docs/clouds.md, "The horizon"):
  //   - the rows' mean luminance, the 12 rows above the horizon: 5.0 % RMS off; 17 % with the
  //     far field before the calibrated mean (a haze 15-33 % too bright 5-11 degrees up), 5.4 %
  //     with no level of detail at all. Tolerance 8 %.
  //   - the variance between neighbours along the 6 rows above the horizon: 2.9x the
  //     supersampled render's; 6.2x with no level of detail and no band rays (speckle), 1.0x
  //     under the haze, which hid the clouds between. Tolerance 3.5x.
  const std::vector<std::string> view = {"camera.pitch=5"};
  const int w = 96, h = 54, s = 4;
  const RenderedFrame small = render(peerView(w, h, view));
  const RenderedFrame large = render(peerView(w * s, h * s, view));
  const Beauty a(small), b(large);
  std::vector<double> la(static_cast<size_t>(w) * h), lb(la.size(), 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      la[static_cast<size_t>(y) * w + x] = a.lum(x, y);
      for (int j = 0; j < s; ++j)
        for (int i = 0; i < s; ++i)
          lb[static_cast<size_t>(y) * w + x] += b.lum(x * s + i, y * s + j);
      lb[static_cast<size_t>(y) * w + x] /= s * s;
    }
  // The horizon row: the first row from the top whose centre ray points below the horizon
  // (the camera is 10 m up: the ground).
  const CameraSettings cam = peerView(w, h, view).camera;
  int horizon = h;
  for (int y = 0; y < h; ++y)
    if (test::pixelDirection(cam, w, h, w / 2, y).z < 0.0f) {
      horizon = y;
      break;
    }
  ASSERT_GT(horizon, 12);
  ASSERT_LT(horizon, h);
  const int y0 = horizon - 6, y1 = horizon;  // about 6 degrees of sky above the horizon
  const double va = adjacentVariance(la, w, y0, y1), vb = adjacentVariance(lb, w, y0, y1);
  double rowErr2 = 0.0;
  for (int y = horizon - 12; y < horizon; ++y) {
    double ma = 0.0, mb = 0.0;
    for (int x = 0; x < w; ++x) {
      ma += la[static_cast<size_t>(y) * w + x];
      mb += lb[static_cast<size_t>(y) * w + x];
    }
    rowErr2 += (ma / mb - 1.0) * (ma / mb - 1.0);
  }
  const double rowRms = std::sqrt(rowErr2 / 12.0);
  std::cout << "horizon band rows " << y0 << "-" << y1 << ": variance " << va << ", supersampled "
            << vb << " (" << va / vb << "x); the 12 rows' means " << 100.0 * rowRms
            << " % RMS off\n";
  EXPECT_LT(va, 3.5 * vb + 1e-6);
  EXPECT_LT(rowRms, 0.08);
}

// The README's default view (configs/default.yaml, pitch 10) at 160 x 90 against the same
// view at 640 x 360 box-filtered to 160 x 90: the rows whose centre rays rise 0-4 degrees,
// the band of small distant clouds, within 10 % RMS of the supersampled luminance. Measured
// 8.6 %, and 15.7 % with one ray a pixel hitting or missing each small cloud at random; at
// 320 x 180 (issue 30's goal: 6 %) 6.0 % and 21 % (docs/clouds.md, "The horizon"). With the
// band's rays 4.1 %; 7.5 % since the far field's mean was measured (the lowest rows, the far
// field alone, a little brighter than the supersampled clouds where its haze was darker).
TEST_F(CloudLookTest, TheDefaultViewsHorizonBandMatchesASupersampledRender) {
  auto view = [](int w, int h) {
    return loadSceneFile(configDir() / "default.yaml", {"output.width=" + std::to_string(w),
                                                        "output.height=" + std::to_string(h)});
  };
  const int w = 160, h = 90, s = 4;
  const RenderedFrame small = render(view(w, h));
  const RenderedFrame large = render(view(w * s, h * s));
  const Beauty a(small), b(large);
  const CameraSettings cam = view(w, h).camera;
  double diff2 = 0.0, sum = 0.0;
  int n = 0;
  for (int y = 0; y < h; ++y) {
    const float rise = test::pixelDirection(cam, w, h, w / 2, y).z;
    if (rise < 0.0f || rise > std::sin(4.0f * static_cast<float>(M_PI) / 180.0f)) continue;
    for (int x = 0; x < w; ++x) {
      double ss = 0.0;
      for (int j = 0; j < s; ++j)
        for (int i = 0; i < s; ++i) ss += b.lum(x * s + i, y * s + j);
      ss /= s * s;
      diff2 += (a.lum(x, y) - ss) * (a.lum(x, y) - ss);
      sum += ss;
      ++n;
    }
  }
  ASSERT_GE(n, 3 * w) << "at least three rows in the band";
  const double rms = std::sqrt(diff2 / n) / (sum / n);
  std::cout << "default view's horizon band: " << n / w << " rows, " << 100.0 * rms
            << " % RMS off the supersampled render\n";
  EXPECT_LT(rms, 0.10);
}

// The power of the frequency of k cycles across the width, per row (the row's DFT
// coefficient at k), averaged over rows: what a pattern repeating along rows leaves.
double rowPower(const std::vector<double>& v, int width, int height, int k) {
  double power = 0.0;
  for (int y = 0; y < height; ++y) {
    double re = 0.0, im = 0.0;
    for (int x = 0; x < width; ++x) {
      const double a = 2.0 * M_PI * k * x / width;
      re += v[static_cast<size_t>(y) * width + x] * std::cos(a);
      im += v[static_cast<size_t>(y) * width + x] * std::sin(a);
    }
    power += (re * re + im * im) / width;
  }
  return power / height;
}

// The same down the columns.
double columnPower(const std::vector<double>& v, int width, int height, int k) {
  std::vector<double> t(v.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      t[static_cast<size_t>(x) * height + y] = v[static_cast<size_t>(y) * width + x];
  return rowPower(t, height, width, k);
}

// The power of the 2 x 2 checkerboard (-1)^(x + y) over the whole image, normalised like
// rowPower (for white noise both have the noise's variance as their mean).
double checkerPower(const std::vector<double>& v, int width, int height) {
  double sum = 0.0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      sum += ((x + y) % 2 ? -1.0 : 1.0) * v[static_cast<size_t>(y) * width + x];
  return sum * sum / (static_cast<double>(width) * height);
}

// Row-coherent fine structure: the square of each 16-pixel run's mean second difference down
// the image (rows = true) or across it (rows = false), averaged over the runs. A line one row
// brighter or darker than its neighbours along a whole run adds to the first; grain averages
// out along a run and adds as much to both.
double coherentLineEnergy(const Beauty& b, bool rows) {
  const int run = 16;
  const int along = rows ? b.width : b.height, across = rows ? b.height : b.width;
  auto lum = [&](int a, int c) { return rows ? b.lum(a, c) : b.lum(c, a); };
  double sum = 0.0;
  int count = 0;
  for (int c = 1; c + 1 < across; ++c)
    for (int a0 = 0; a0 + run <= along; a0 += run) {
      double m = 0.0;
      for (int a = a0; a < a0 + run; ++a) m += lum(a, c) - 0.5 * (lum(a, c - 1) + lum(a, c + 1));
      m /= run;
      sum += m * m;
      ++count;
    }
  return sum / count;
}

TEST_F(CloudLookTest, NoHorizontalStriationsAcrossDistantClouds) {
  // Sunlit cumulus about 10 km away, seen at the size of a pixel of the 1280 x 720 peer view
  // (a 4.5 degree field of view at 96 x 54). Strides through the clear air right beside the
  // clouds hit or missed their fringes alike along whole rows, as thin horizontal lines. The
  // lines' energy (along rows, less the grain's, measured across columns) must stay near that
  // of a converged march of 5 m steps, whose own is the clouds' layering seen edge-on.
  const std::vector<std::string> view = {"camera.pitch=10.5", "camera.vertical_fov=4.5"};
  std::vector<std::string> fine = view;
  fine.push_back("clouds.step_m=5");
  fine.push_back("clouds.step_growth=0.0005");
  const RenderedFrame f = render(peerView(96, 54, view));
  const RenderedFrame ref = render(peerView(96, 54, fine));
  const Beauty b(f), r(ref);
  const CloudLayerView c(f);
  int covered = 0;
  for (int y = 0; y < b.height; ++y)
    for (int x = 0; x < b.width; ++x) covered += c.at(x, y).alpha > 0.95f;
  ASSERT_GT(covered, b.width * b.height / 2) << "the view is mostly cloud";
  const double lines = coherentLineEnergy(b, true) - coherentLineEnergy(b, false);
  const double refLines = coherentLineEnergy(r, true) - coherentLineEnergy(r, false);
  std::cout << "striations: row-coherent energy " << lines << ", converged march " << refLines
            << "\n";
  ASSERT_GT(refLines, 0.0);
  // Measured: 1.06x (strides limited by the clearance); strides that ignored it, 11x.
  EXPECT_LT(lines, 3.0 * refLines);
}

// How much fine structure (cells, billows) a view of cloud shows: the clouds' luminance over
// 4 x 4 blocks (which average the march's grain away), each opaque block's relative difference
// from the mean of its four neighbours, averaged. The view's slow gradients do not count.
double cellContrast(const RenderedFrame& f) {
  const CloudLayerView c(f);
  const int n = 4;
  const int bw = c.width() / n, bh = c.height() / n;
  std::vector<double> block(static_cast<size_t>(bw) * bh, -1.0);  // -1: not opaque
  for (int by = 0; by < bh; ++by)
    for (int bx = 0; bx < bw; ++bx) {
      double sum = 0.0;
      bool opaque = true;
      for (int k = 0; k < n * n; ++k) {
        const test::CloudPixel p = c.at(n * bx + k % n, n * by + k / n);
        opaque = opaque && p.alpha > 0.95f;
        sum += test::luminance(&p.rgb.x);
      }
      if (opaque) block[static_cast<size_t>(by) * bw + bx] = sum / (n * n);
    }
  auto at = [&](int x, int y) { return block[static_cast<size_t>(y) * bw + x]; };
  double sum = 0.0;
  int count = 0;
  for (int y = 1; y + 1 < bh; ++y)
    for (int x = 1; x + 1 < bw; ++x) {
      const double b = at(x, y), l = at(x - 1, y), r = at(x + 1, y), u = at(x, y - 1),
                   d = at(x, y + 1);
      if (std::min({b, l, r, u, d}) <= 0.0) continue;
      sum += std::abs(b - 0.25 * (l + r + u + d)) / b;
      ++count;
    }
  return count > 0 ? sum / count : 0.0;
}

TEST_F(CloudLookTest, AltostratusIsASmootherSheetThanAltocumulus) {
  // The same mid layer at 80 % cover from the ground at noon, as altostratus and as
  // altocumulus: the density read the type only through its height range, so both showed the
  // same cells. The stratiform sheet keeps the shape's low octave alone (cloudTypeTexture).
  // (The test used 70 %, where the sheet came out 0.08 more covered than the map until issue
  // 30 fixed the calibration; with the sheet's holes as the map says, the ratio there is 0.98x.)
  auto view = [&](const std::string& type) {
    return render(loadSceneFile(configDir() / "examples" / "cumulus_noon.yaml",
                                {"output.width=192", "output.height=108", "weather.cover_low=0",
                                 "weather.cover_mid=0.8", "weather.cloud_type=" + type}));
  };
  const double sheet = cellContrast(view("altostratus"));
  const double cells = cellContrast(view("altocumulus"));
  std::cout << "cell contrast: altostratus " << sheet << ", altocumulus " << cells << "\n";
  ASSERT_GT(cells, 0.0) << "the altocumulus shows structure";
  // Measured at 192 x 108: 0.81x (at 70 % before issue 30, 0.84x); with the type read only
  // through the height range, 1.23x (the altostratus sheet is thicker, so its cells shadowed
  // each other more).
  EXPECT_LT(sheet, 0.95 * cells);
}

// Seen from above, how much faster a field changes north-south than east-west: the mean
// squared difference of the opacity `lag` pixels apart down the columns over that along the
// rows. 1 for round cells; above 1 for rolls running east-west.
double northSouthOverEastWest(const CloudLayerView& c, int lag) {
  const std::vector<float> a = c.alpha();
  const int w = c.width(), h = c.height();
  auto at = [&](int x, int y) { return static_cast<double>(a[static_cast<size_t>(y) * w + x]); };
  double ns = 0.0, ew = 0.0;
  for (int y = 0; y + lag < h; ++y)
    for (int x = 0; x + lag < w; ++x) {
      ns += (at(x, y + lag) - at(x, y)) * (at(x, y + lag) - at(x, y));
      ew += (at(x + lag, y) - at(x, y)) * (at(x + lag, y) - at(x, y));
    }
  return ew > 0.0 ? ns / ew : 0.0;
}

TEST_F(CloudLookTest, StratocumulusRunsInRollsAlongTheWind) {
  // Top-down over 33 x 33 km at 50 % cover (96 x 96 px, 350 m a pixel): the shape noise's
  // 1.25 km cells are 3.5 px across. Stratocumulus lines up in rolls along the wind
  // (cloudRollWeight), cumulus and altocumulus keep round cells, whatever the wind.
  auto view = [&](const std::string& type, const std::string& windFrom) {
    const bool mid = type == "altocumulus";
    return render(
        loadSceneFile(configDir() / "examples" / "topdown_dsc.yaml",
                      {"output.width=96", "output.height=96", "weather.region.lat=[47, 47.3]",
                       "weather.region.lon=[8, 8.44]", "weather.spread=0",
                       std::string("weather.cover_low=") + (mid ? "0" : "0.5"),
                       std::string("weather.cover_mid=") + (mid ? "0.5" : "0"),
                       "weather.cloud_type=" + type, "clouds.wind_from=" + windFrom}));
  };
  const double westerly = northSouthOverEastWest(CloudLayerView(view("stratocumulus", "270")), 3);
  const double northerly = northSouthOverEastWest(CloudLayerView(view("stratocumulus", "0")), 3);
  const double cumulus = northSouthOverEastWest(CloudLayerView(view("cumulus", "270")), 3);
  const double altocumulus = northSouthOverEastWest(CloudLayerView(view("altocumulus", "270")), 3);
  std::cout << "north-south over east-west change at 1 km: stratocumulus, west wind " << westerly
            << ", north wind " << northerly << "; cumulus " << cumulus << "; altocumulus "
            << altocumulus << "\n";
  // Measured: 2.15 and 0.43 (rolls 4x longer than wide; the detail noise stays round);
  // without the rolls, stratocumulus is as round as the others (about 1).
  EXPECT_GT(westerly, 1.7) << "rolls run east-west under a west wind";
  EXPECT_LT(northerly, 1.0 / 1.7) << "and north-south under a north wind";
  EXPECT_NEAR(cumulus, 1.0, 0.35) << "cumulus cells stay round";
  EXPECT_NEAR(altocumulus, 1.0, 0.35) << "altocumulus cells stay round";
}

TEST_F(CloudLookTest, NoPeriodicDitherPattern) {
  // The top-down example (topdown_dsc) and the view from 5 km, where a 2 x 2 checkerboard
  // showed in shadows and at edges, with 120 m steps so the start jitter shows plainly. No
  // frequency between a quarter and half the sampling rate may stand out in the clouds' luminance
  // (along rows, down columns, or as the 2 x 2 checkerboard). White noise has no peak; interleaved
  // gradient noise, whose neighbours along a row differ by 0.555, has one near a 2.25-pixel period.
  // (With steps limited to half an optical depth inside clouds, the jitter no longer shows a
  // pattern even with that noise; the test keeps it from coming back.)
  const std::vector<Scene> scenes = {
      [] {
        Scene s = loadSceneFile(configDir() / "examples" / "topdown_dsc.yaml",
                                {"output.width=96", "output.height=96", "clouds.step_m=120"});
        return s;
      }(),
      peerView(96, 54, {"camera.altitude_m=5000", "camera.pitch=-15", "clouds.step_m=120"})};
  for (const Scene& scene : scenes) {
    const RenderedFrame f = render(scene);
    const CloudLayerView c(f);
    const int w = c.width(), h = c.height();
    std::vector<double> lum(static_cast<size_t>(w) * h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const glm::vec3 rgb = c.at(x, y).rgb;
        lum[static_cast<size_t>(y) * w + x] = test::luminance(&rgb.x);
      }
    // The high band, a quarter of the sampling rate up to half (the 2-pixel period), along
    // rows and down columns: each frequency's power averaged over the rows (or columns), so
    // noise scatters by about a seventh around its level. A periodic pattern stands out as
    // a peak over the band's median; noise and the picture (whose power falls with frequency)
    // do not.
    auto peakOf = [&](const std::vector<double>& v, bool columns) {
      const int n = columns ? h : w;
      std::vector<double> p;
      for (int k = n / 4; k <= n / 2; ++k)
        p.push_back(columns ? columnPower(v, w, h, k) : rowPower(v, w, h, k));
      std::vector<double> sorted = p;
      std::sort(sorted.begin(), sorted.end());
      const double median = sorted[sorted.size() / 2];
      return std::pair{sorted.back() / median, median};
    };
    const auto [rowPeak, rowMedian] = peakOf(lum, false);
    const auto [columnPeak, columnMedian] = peakOf(lum, true);
    // The measure can see such a pattern: interleaved gradient noise (the old jitter) of a
    // the mean luminance peak to peak (a plain dither), added to the same image, stands out.
    {
      double mean = 0.0;
      for (double v : lum) mean += v;
      mean /= static_cast<double>(lum.size());
      std::vector<double> dithered = lum;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const double ign = std::fmod(
              52.9829189 * std::fmod(0.06711056 * (x + 0.5) + 0.00583715 * (y + 0.5), 1.0), 1.0);
          dithered[static_cast<size_t>(y) * w + x] += mean * (ign - 0.5);
        }
      EXPECT_GT(peakOf(dithered, false).first, 2.0) << "the measure misses a known pattern";
    }
    // The 2 x 2 checkerboard, one coefficient over the whole image: it scatters like an
    // exponential variable around the noise level, hence the wider bound.
    const double checker = checkerPower(lum, w, h) / rowMedian;
    std::cout << scene.output.name << ": high-band peak over median along rows " << rowPeak
              << ", columns " << columnPeak << "; checkerboard over the row median " << checker
              << "\n";
    ASSERT_GT(rowMedian, 0.0) << "the clouds show some detail to measure";
    // Measured: 1.2-1.7 (the picture's own edges); the known dither above reaches 2.1 and more.
    EXPECT_LT(rowPeak, 2.0) << scene.output.name;
    EXPECT_LT(columnPeak, 2.0) << scene.output.name;
    EXPECT_LT(checker, 8.0) << scene.output.name;
  }
}

// A ray stopped by transmittance_cutoff is taken as opaque, what is left of its transmittance
// lit like its last sample (volumetric_clouds.comp): an overcast looks the same whether its
// rays stop at 10 % or at 0.1 %, not 10 % see-through and darker. Over the pixels the late
// stop finds opaque, the early stop's opacity must be 1 and its mean luminance within 2 % of
// the late stop's. Measured: opacity 1, luminance ratio 0.999; with the rest left out (as
// before issue 16's last session) the opacity was 0.90 and the ratio 0.93.
TEST_F(CloudLookTest, ARayCutOffEarlyLooksLikeTheCloudMarchedOn) {
  auto overcast = [](const char* cutoff) {
    return test::cloudScene("overcast_stratus",
                            {"output.width=64", "output.height=36",
                             std::string("clouds.transmittance_cutoff=") + cutoff});
  };
  const RenderedFrame earlyFrame = render(overcast("0.1"));
  const RenderedFrame lateFrame = render(overcast("0.001"));
  const CloudLayerView early(earlyFrame), late(lateFrame);
  double sumEarly = 0.0, sumLate = 0.0;
  float minAlpha = 1.0f;
  int n = 0;
  for (int y = 0; y < late.height(); ++y)
    for (int x = 0; x < late.width(); ++x) {
      const test::CloudPixel l = late.at(x, y), e = early.at(x, y);
      if (l.alpha < 0.999f) continue;
      ++n;
      sumEarly += test::luminance(&e.rgb.x);
      sumLate += test::luminance(&l.rgb.x);
      minAlpha = std::min(minAlpha, e.alpha);
    }
  const double ratio = sumLate > 0.0 ? sumEarly / sumLate : 0.0;
  std::printf("%d opaque pixels: early stop's opacity at least %.4f, luminance ratio %.4f\n", n,
              minAlpha, ratio);
  ASSERT_GT(n, late.width() * late.height() / 4) << "the overcast must be opaque overhead";
  EXPECT_GE(minAlpha, 0.9999f);
  EXPECT_NEAR(ratio, 1.0, 0.02);
}

}  // namespace
}  // namespace sky
