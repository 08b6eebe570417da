// passes/star_field on the device, read back through shaders/common/star_field.glsl (a test
// shader copies starFlux and pixelSolidAngle into an image the graph reads back): the whole
// catalogue against a C++ reference splat, a synthetic star's bilinear weights and smooth
// motion, the horizon fade, the per-star clamp and the pixel solid angle.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <gtest/gtest.h>

#include "engine/core/paths.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/graph/pass_context.h"
#include "engine/lighting/star_catalog.h"
#include "engine/shader/shader_compiler.h"
#include "gpu_test.h"
#include "passes/star_field/star_field.h"

namespace sky {
namespace {
namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kCount = 1.0 / 65536.0;  // one fixed-point count of the flux buffer
constexpr uint32_t kW = 64, kH = 36;

glm::dvec3 azEl(double azDeg, double elDeg) {
  return {std::sin(azDeg * kDeg) * std::cos(elDeg * kDeg),
          std::cos(azDeg * kDeg) * std::cos(elDeg * kDeg), std::sin(elDeg * kDeg)};
}

// A pinhole camera in the east-north-up frame, built the way engine/render/camera.cpp does.
shared::ViewState makeView(double headingDeg, double pitchDeg, double vfovDeg, uint32_t w = kW,
                           uint32_t h = kH) {
  const glm::dvec3 forward = azEl(headingDeg, pitchDeg);
  const glm::dvec3 right = azEl(headingDeg + 90.0, 0.0);
  const glm::dvec3 up = glm::normalize(glm::cross(right, forward));
  const double tanV = std::tan(0.5 * vfovDeg * kDeg), tanH = tanV * w / h;
  shared::ViewState v{};
  v.right = glm::vec4(glm::vec3(right), static_cast<float>(tanH));
  v.up = glm::vec4(glm::vec3(up), static_cast<float>(tanV));
  v.forward = glm::vec4(glm::vec3(forward), static_cast<float>(2.0 * tanV / h));
  v.size = glm::uvec4(w, h, 0, 0);
  return v;
}

// Direction through continuous pixel coordinates (centre of pixel (i, j) = (i + 0.5, j + 0.5)),
// as viewDirection in shaders/common/view.glsl, in double.
glm::dvec3 directionThrough(const shared::ViewState& v, glm::dvec2 pixel) {
  const double nx = pixel.x / v.size.x * 2 - 1, ny = pixel.y / v.size.y * 2 - 1;
  return glm::normalize(glm::dvec3(v.forward) + nx * double(v.right.w) * glm::dvec3(v.right) -
                        ny * double(v.up.w) * glm::dvec3(v.up));
}

// J2000 -> east-north-up for latitude `lat` and local sidereal time `lst` (degrees), ignoring
// precession: the rows are east, north and up written in J2000 coordinates.
glm::dmat3 equatorialToEnu(double latDeg, double lstDeg) {
  const double phi = latDeg * kDeg, t = lstDeg * kDeg;
  const glm::dvec3 meridian(std::cos(t), std::sin(t), 0), pole(0, 0, 1);
  const glm::dvec3 east(-std::sin(t), std::cos(t), 0);
  const glm::dvec3 north = -std::sin(phi) * meridian + std::cos(phi) * pole;
  const glm::dvec3 up = std::cos(phi) * meridian + std::sin(phi) * pole;
  return glm::transpose(glm::dmat3(east, north, up));
}

// The rotation that takes unit vector a onto unit vector b (Rodrigues).
glm::dmat3 rotationOnto(glm::dvec3 a, glm::dvec3 b) {
  const glm::dvec3 v = glm::cross(a, b);
  const double c = glm::dot(a, b);
  const glm::dmat3 k(glm::dvec3(0, v.z, -v.y), glm::dvec3(-v.z, 0, v.x), glm::dvec3(v.y, -v.x, 0));
  return glm::dmat3(1.0) + k + k * k / (1.0 + c);
}

// Kasten & Young (1989) air mass at elevation h (degrees).
double airMass(double hDeg) {
  return 1.0 / (std::sin(hDeg * kDeg) + 0.50572 * std::pow(hDeg + 6.07995, -1.6364));
}

// The flux a star brings after extinction and the fade below the horizon, unclamped.
double extinctedFlux(double vmag, double elevationDeg, double k) {
  if (elevationDeg <= -0.5) return 0.0;
  const double t = std::clamp((elevationDeg + 0.5) / 0.5, 0.0, 1.0);
  const double fade = t * t * (3 - 2 * t);
  return std::pow(10.0, -0.4 * vmag) *
         std::pow(10.0, -0.4 * k * airMass(std::max(elevationDeg, -0.5))) * fade;
}

struct Reference {
  std::vector<double> flux;  // per pixel, row 0 at the top
  int splatted = 0;          // stars with a footprint in the image
  int hiddenInView = 0;      // stars in the image's frustum but below the horizon
  double total() const {
    double s = 0;
    for (double f : flux) s += f;
    return s;
  }
};

// The star field written independently in double: rotate, project, extinguish, fade, tent.
Reference referenceSplat(const std::vector<Star>& stars, const StarFieldPass::Frame& frame) {
  const shared::ViewState& v = frame.view;
  const glm::dmat3 m(frame.j2000ToEnu);
  Reference ref;
  ref.flux.assign(size_t(v.size.x) * v.size.y, 0.0);
  for (const Star& s : stars) {
    const glm::dvec3 d = m * glm::dvec3(s.directionJ2000);
    const double depth = glm::dot(d, glm::dvec3(v.forward));
    if (depth <= 0) continue;
    const double px = (glm::dot(d, glm::dvec3(v.right)) / (depth * v.right.w) + 1) * 0.5 * v.size.x;
    const double py = (-glm::dot(d, glm::dvec3(v.up)) / (depth * v.up.w) + 1) * 0.5 * v.size.y;
    const double x = px - 0.5, y = py - 0.5;
    const double x0 = std::floor(x), y0 = std::floor(y);
    if (x0 < -1 || y0 < -1 || x0 >= v.size.x || y0 >= v.size.y) continue;
    const double elevation = std::asin(std::clamp(d.z, -1.0, 1.0)) / kDeg;
    const double f = std::min(extinctedFlux(s.vmag, elevation, frame.extinction), 256.0);
    if (f == 0) {
      ++ref.hiddenInView;
      continue;
    }
    ++ref.splatted;
    const double fx = x - x0, fy = y - y0;
    const double w[2][2] = {{(1 - fx) * (1 - fy), fx * (1 - fy)}, {(1 - fx) * fy, fx * fy}};
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const double xi = x0 + i, yj = y0 + j;
        if (xi < 0 || yj < 0 || xi >= v.size.x || yj >= v.size.y) continue;
        ref.flux[size_t(yj) * v.size.x + size_t(xi)] += f * w[j][i];
      }
  }
  return ref;
}

struct Readout {
  std::vector<double> flux;         // starFlux per pixel
  std::vector<double> solidAngle;   // pixelSolidAngle per pixel
  std::vector<double> outsideFlux;  // starFlux one image width to the right: must be 0
  std::vector<std::string> passes;  // in execution order
  double at(uint32_t x, uint32_t y) const { return flux[size_t(y) * kW + x]; }
  double total() const {
    double s = 0;
    for (double f : flux) s += f;
    return s;
  }
};

class StarFieldTest : public test::GpuTest {
protected:
  void SetUp() override {
    if (!mReadout) {
      ShaderCompiler tests(shaderDir(), std::nullopt);
      CompiledShader s = tests.compile(fs::path(std::getenv("SKY_TEST_DATA")) / "star_field" /
                                       "star_flux_readout.comp");
      mReadout =
          std::make_unique<ComputePipeline>(ctx(), "star_flux_readout", s.spirv, s.reflection);
    }
    mRuntime = std::make_unique<GraphRuntime>(ctx());
  }
  static void TearDownTestSuite() { mReadout.reset(); }

  std::unique_ptr<StarFieldPass> makePass(const std::vector<Star>& stars) {
    static ShaderCompiler compiler;
    return std::make_unique<StarFieldPass>(ctx(), compiler, stars);
  }

  // One frame: star_clear, star_field, then the readout through star_field.glsl. The
  // runtime is kept across frames of a test, so the flux buffer's memory is reused and a
  // missing clear would show up as flux carried over.
  Readout render(StarFieldPass& pass, const StarFieldPass::Frame& frame) {
    FrameGraph g(*mRuntime);
    const BufferId flux = pass.addTo(g, frame)->flux;
    const shared::ViewState view = frame.view;
    ImageId out;
    GraphBuilder b = g.addPass("star_readout", [&](PassContext& pc) {
      pc.dispatch(*mReadout,
                  {Binding::of(0, pc.uniform(view)), Binding::of(1, flux), Binding::of(2, out)},
                  mReadout->groupsX(view.size.x), mReadout->groupsY(view.size.y));
    });
    b.read(flux, Access::StorageReadCompute);
    ImageDesc d;
    d.name = "star_readout";
    d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    d.width = view.size.x;
    d.height = view.size.y;
    out = b.write(b.create(d), Access::StorageWriteCompute);
    g.requestOutput(out, "stars");
    const FrameResult r = g.execute();
    const ReadbackImage& img = r.output("stars");
    Readout o;
    for (size_t i = 0; i < size_t(img.width) * img.height; ++i) {
      o.flux.push_back(img.pixels[i * 4 + 0]);
      o.solidAngle.push_back(img.pixels[i * 4 + 1]);
      o.outsideFlux.push_back(img.pixels[i * 4 + 2]);
    }
    for (const PassTiming& t : r.passes) o.passes.push_back(t.name);
    return o;
  }

  static std::unique_ptr<ComputePipeline> mReadout;
  std::unique_ptr<GraphRuntime> mRuntime;
};
std::unique_ptr<ComputePipeline> StarFieldTest::mReadout;

TEST_F(StarFieldTest, CatalogueMatchesTheReferenceSplat) {
  const std::vector<Star> stars =
      loadStarCatalog(configDir() / "stars" / "bright_star_catalogue.txt");
  auto pass = makePass(stars);
  // Two frames through the same runtime: a low view across the horizon (extinction, stars
  // cut off below it) from 48 N, then a view toward the zenith half a sidereal day later.
  const StarFieldPass::Frame frames[] = {
      {makeView(160, 12, 50), glm::mat3(equatorialToEnu(48, 100)), 0.25f},
      {makeView(20, 70, 60), glm::mat3(equatorialToEnu(48, 280)), 0.15f},
  };
  for (const StarFieldPass::Frame& frame : frames) {
    const Reference ref = referenceSplat(stars, frame);
    ASSERT_GT(ref.splatted, 80) << "the view should hold many stars";
    const Readout got = render(*pass, frame);
    EXPECT_EQ(got.passes,
              (std::vector<std::string>{"star_clear", "star_field", "star_readout", "readback"}));
    EXPECT_NEAR(got.total(), ref.total(), 1e-3 * ref.total()) << "total splatted flux";
    double worst = 0;
    for (size_t i = 0; i < ref.flux.size(); ++i) {
      // Rounding to counts (half a count per star and pixel) and float projection.
      const double tolerance = 1e-3 * ref.flux[i] + 4 * kCount;
      worst = std::max(worst, std::abs(got.flux[i] - ref.flux[i]) / tolerance);
      ASSERT_EQ(got.outsideFlux[i], 0.0);
    }
    EXPECT_LE(worst, 1.0) << "largest per-pixel error in units of the tolerance";
  }
  EXPECT_GT(referenceSplat(stars, frames[0]).hiddenInView, 20) << "stars below the horizon in view";
}

TEST_F(StarFieldTest, SyntheticStarLandsOnFourPixelsWithBilinearWeights) {
  const glm::dvec3 star = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
  auto pass = makePass({{glm::vec3(star), 0.0f}});
  const shared::ViewState view = makeView(30, 45, 40);
  // Place the star at continuous pixel (10.8, 21.2): 0.3 right and 0.7 below the centre of
  // pixel (10, 20). Without extinction a V = 0 star brings flux 1.
  const glm::dvec3 target = directionThrough(view, {10.8, 21.2});
  const Readout got = render(*pass, {view, glm::mat3(rotationOnto(star, target)), 0.0f});
  const double tol = 2 * kCount;
  EXPECT_NEAR(got.at(10, 20), 0.7 * 0.3, tol);
  EXPECT_NEAR(got.at(11, 20), 0.3 * 0.3, tol);
  EXPECT_NEAR(got.at(10, 21), 0.7 * 0.7, tol);
  EXPECT_NEAR(got.at(11, 21), 0.3 * 0.7, tol);
  EXPECT_NEAR(got.total(), 1.0, tol);
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x)
      if ((x != 10 && x != 11) || (y != 20 && y != 21)) {
        ASSERT_EQ(got.at(x, y), 0.0) << x << "," << y;
      }

  // With extinction k the star is dimmed by 10^(-0.4 k X) at its own elevation.
  const double k = 0.3, elevation = std::asin(target.z) / kDeg;
  const Readout dimmed = render(*pass, {view, glm::mat3(rotationOnto(star, target)), float(k)});
  EXPECT_NEAR(dimmed.total(), extinctedFlux(0.0, elevation, k), 1e-4);

  // At the left border only the in-image half of the footprint lands: pixel 0.2 across
  // puts 0.7 of the star in column 0 and 0.3 outside.
  const Readout border = render(
      *pass, {view, glm::mat3(rotationOnto(star, directionThrough(view, {0.2, 5.5}))), 0.0f});
  EXPECT_NEAR(border.at(0, 5), 0.7, tol);
  EXPECT_NEAR(border.total(), 0.7, tol);
}

TEST_F(StarFieldTest, MovingStarMovesItsCentroidSmoothly) {
  // A time-lapse in miniature: the star crosses two pixels in 17 steps. The tent keeps the
  // flux constant and puts the centroid exactly where the star is, so nothing flickers.
  const glm::dvec3 star(0, 0, 1);
  auto pass = makePass({{glm::vec3(star), 1.0f}});
  const shared::ViewState view = makeView(200, 30, 40);
  const double flux = std::pow(10.0, -0.4);
  for (int step = 0; step <= 16; ++step) {
    const glm::dvec2 at(30.0 + step / 8.0, 17.3);
    const Readout got =
        render(*pass, {view, glm::mat3(rotationOnto(star, directionThrough(view, at))), 0.0f});
    double sum = 0, sx = 0, sy = 0;
    for (uint32_t y = 0; y < kH; ++y)
      for (uint32_t x = 0; x < kW; ++x) {
        sum += got.at(x, y);
        sx += got.at(x, y) * (x + 0.5);
        sy += got.at(x, y) * (y + 0.5);
      }
    ASSERT_NEAR(sum, flux, 4 * kCount) << "step " << step;
    EXPECT_NEAR(sx / sum, at.x, 1e-3) << "step " << step;
    EXPECT_NEAR(sy / sum, at.y, 1e-3) << "step " << step;
  }
}

TEST_F(StarFieldTest, StarsFadeOutJustBelowTheHorizon) {
  // Level camera: the horizon runs through the middle of the image. Each star on its own,
  // so its total is exactly what it contributes.
  const shared::ViewState view = makeView(90, 0, 30);
  const double k = 0.1;
  auto total = [&](double elevationDeg) {
    auto pass = makePass({{glm::vec3(azEl(90, elevationDeg)), 0.0f}});
    return render(*pass, {view, glm::mat3(1.0f), float(k)}).total();
  };
  EXPECT_EQ(total(-0.6), 0.0) << "below the fade band";
  EXPECT_EQ(total(-0.5001), 0.0);
  for (double e : {-0.4, -0.25, -0.1, 0.0, 0.2, 3.0}) {
    const double want = extinctedFlux(0.0, e, k);
    EXPECT_NEAR(total(e), want, 1e-3 * want + 4 * kCount) << "elevation " << e;
  }
  // The fade is continuous: 0.02 degree steps change the flux by a small fraction of the
  // horizon flux, never a jump.
  double previous = total(-0.52);
  const double horizon = extinctedFlux(0.0, 0.0, k);
  for (double e = -0.50; e <= 0.1; e += 0.02) {
    const double f = total(e);
    EXPECT_LT(std::abs(f - previous), 0.12 * horizon) << "elevation " << e;
    previous = f;
  }

  // A star behind the camera is skipped even though it is above the horizon.
  auto behind = makePass({{glm::vec3(azEl(270, 5)), 0.0f}});
  EXPECT_EQ(render(*behind, {view, glm::mat3(1.0f), 0.0f}).total(), 0.0);
}

TEST_F(StarFieldTest, OneStarIsClampedSoPixelsCannotOverflow) {
  // V = -10 would be 10^4 V = 0 stars; one star is clamped to 256 (2^24 counts), so a pixel
  // overflows only after 256 such stars or 65536 V = 0 stars (star_field_shared.h).
  const shared::ViewState view = makeView(0, 40, 40);
  const glm::dvec3 star(1, 0, 0);
  auto pass = makePass({{glm::vec3(star), -10.0f}});
  const Readout got = render(
      *pass, {view, glm::mat3(rotationOnto(star, directionThrough(view, {20.5, 10.5}))), 0.0f});
  // The star sits on a pixel centre up to float rounding of its direction (~1e-5 pixel).
  EXPECT_NEAR(got.at(20, 10), 256.0, 0.01);
  EXPECT_NEAR(got.total(), 256.0, 4 * kCount);
}

TEST_F(StarFieldTest, PixelSolidAnglesAreExactAndSumToTheImage) {
  // A wide 120 degree view at an odd size, where pixels at the corners are much smaller
  // than at the centre.
  const uint32_t w = 97, h = 41;
  const shared::ViewState view = makeView(10, 20, 120, w, h);
  auto pass = makePass({{glm::vec3(0, 0, 1), 0.0f}});
  const Readout got = render(*pass, {view, glm::mat3(1.0f), 0.0f});
  const double tx = view.right.w, ty = view.up.w;
  // The solid angle of the image-plane rectangle [u0, u1] x [v0, v1] at unit distance:
  // the sum of atan(u v / sqrt(1 + u^2 + v^2)) over its corners with alternating signs.
  auto rect = [](double u0, double u1, double v0, double v1) {
    auto f = [](double u, double v) { return std::atan(u * v / std::sqrt(1 + u * u + v * v)); };
    return f(u1, v1) - f(u0, v1) - f(u1, v0) + f(u0, v0);
  };
  double sum = 0, worst = 0;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const double u0 = (2.0 * x / w - 1) * tx, u1 = (2.0 * (x + 1) / w - 1) * tx;
      const double v0 = (1 - 2.0 * (y + 1) / h) * ty, v1 = (1 - 2.0 * y / h) * ty;
      const double want = rect(u0, u1, v0, v1);
      const double got1 = got.solidAngle[size_t(y) * w + x];
      worst = std::max(worst, std::abs(got1 - want) / want);
      sum += got1;
    }
  EXPECT_LT(worst, 3e-6) << "largest relative error of one pixel's solid angle";
  EXPECT_NEAR(sum, rect(-tx, tx, -ty, ty), 1e-6 * sum) << "the pixels tile the image";
}

}  // namespace
}  // namespace sky
