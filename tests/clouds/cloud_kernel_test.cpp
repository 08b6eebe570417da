// shaders/common/cloud_density.glsl, cloud_lighting.glsl and cloud_light_march.glsl against
// their C++ twins (engine/clouds/cloud_math.h) in Falcor's kernel-test style: cloud_kernel.comp
// evaluates every function on 256 queries spread over its inputs, the results come back and
// the twin evaluates the same inputs. Plus what only the GPU run can show: Ei at tabulated
// points, one octave of in-scattering being Lu (22) * (23), the light march against analytic
// integrals and the energy-conserving step against the exact solution.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "engine/clouds/cloud_math.h"
#include "engine/core/paths.h"
#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/graph/pass_context.h"
#include "engine/shader/shader_compiler.h"
#include "gpu_test.h"

namespace sky::test {
namespace {
using namespace sky::clouds;

constexpr int kQueries = 256;  // KERNEL_QUERIES in cloud_kernel.comp
constexpr int kGroup = 64;     // KERNEL_GROUP
constexpr int kRows = 28;

// What each row of the results image holds (cloud_kernel.comp writes them in this order).
enum KernelRow {
  kInputs0,
  kInputs1,
  kInputs2,
  kHelpers,      // luRemap, luSat, luLerp, luFbm
  kHeightShape,  // GSb, GSt, GS, GDb
  kHeightDensity,
  kDetail,
  kComposed,
  kTypeRanges,
  kTang,
  kPhase,
  kAmbientScalars,
  kAmbient,
  kInScatter,
  kIntegrate,
  kIntegrateInputs,
  kSchedule,
  kMarch,
  kMarchLight,
  kMarchPoint,
  kEnergy,
  kDiffusion,       // diffuseTransmittance, cloudDiffuseInScatter, cloudEdgeDensity, leak
  kAmbientDiffuse,  // cloudAmbientDiffuse
  kRollWeight,      // cloudRollWeight, low and mid layer; cloudPhaseSkyLight; cloudFarExtinction
  kMarchSplit,      // lightMarchDepth's own and beyond: the slab, the slab with a gap
  kCumulusShape,    // cloudCumulusWeight, cumulusOutline, cumulusShape's R and G
  kCumulusDensity,  // cumulusGD, cumulusNDmod, cumulusCloudDensity, the weight
  kBehindShare,     // diffuseBehindShare inside, at the lit face, at the far face, thick
};

// Float maths on lavapipe against float maths in C++: exp, log, pow and division differ in the
// last bits (lavapipe's exp and log are good to about 1e-7 relative). 2e-6 absolute plus 1e-5
// relative leaves room for a few such steps in a row; a wrong formula is off by far more.
constexpr double kAbs = 2e-6, kRel = 1e-5;

class CloudKernelTest : public GpuTest {
protected:
  static void SetUpTestSuite() {
    ShaderCompiler compiler(shaderDir(), std::nullopt);
    const CompiledShader shader =
        compiler.compile(std::filesystem::path(SKY_CLOUDS_TEST_DIR) / "cloud_kernel.comp");
    ComputePipeline pipeline(sharedContext(), "cloud_kernel", shader.spirv, shader.reflection);
    GraphRuntime runtime(sharedContext());
    FrameGraph graph(runtime);
    ImageId results;
    GraphBuilder b = graph.addPass("cloud_kernel", [&](PassContext& pc) {
      pc.dispatch(pipeline, {Binding::of(0, results)}, kQueries / kGroup, 1);
    });
    ImageDesc d;
    d.name = "results";
    d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    d.width = kQueries;
    d.height = kRows;
    results = b.write(b.create(d), Access::StorageWriteCompute);
    graph.requestOutput(results, "results");
    sPixels = graph.execute().output("results").pixels;
  }

  // Component c of row `row` for query i.
  static float at(int row, int i, int c) {
    return sPixels[(size_t(row) * kQueries + size_t(i)) * 4 + size_t(c)];
  }
  static glm::vec4 row(int r, int i) {
    return {at(r, i, 0), at(r, i, 1), at(r, i, 2), at(r, i, 3)};
  }

  // Every component of `row` against the twin's values, with a name per component.
  static void expectRow(int r, int i, glm::vec4 want, const char* const names[4],
                        double relTolerance = kRel) {
    for (int c = 0; c < 4; ++c) {
      EXPECT_NEAR(at(r, i, c), want[c], kAbs + relTolerance * std::abs(want[c]))
          << names[c] << " at query " << i;
      const double error = std::abs(at(r, i, c) - want[c]);
      sWorstAbs = std::max(sWorstAbs, error);
      if (std::abs(want[c]) > 1e-3) sWorstRel = std::max(sWorstRel, error / std::abs(want[c]));
    }
  }
  static void printWorst(const char* what) {
    std::cout << what << ": worst GLSL - C++ difference " << sWorstAbs << " absolute, " << sWorstRel
              << " relative (values above 1e-3)\n";
    sWorstAbs = sWorstRel = 0;
  }

  static std::vector<float> sPixels;
  static double sWorstAbs, sWorstRel;
};
std::vector<float> CloudKernelTest::sPixels;
double CloudKernelTest::sWorstAbs = 0, CloudKernelTest::sWorstRel = 0;

// The inputs cloud_kernel.comp derived from query i's three input rows.
struct Inputs {
  glm::vec4 r0, r1, r2;
  float ph, cmc, threshold, v, type;
  glm::vec4 shape;
  glm::vec3 detail;
};

Inputs inputsOf(glm::vec4 r0, glm::vec4 r1, glm::vec4 r2) {
  Inputs in{r0,
            r1,
            r2,
            -0.1f + 1.2f * r0.x,
            r0.y,
            -0.5f + 1.6f * r2.y,
            2.0f * r2.z - 0.5f,
            -0.1f + 1.2f * r2.w,
            glm::vec4(r0.z, r0.w, r1.x, r1.y),
            glm::vec3(r1.z, r1.w, r2.x)};
  return in;
}

TEST_F(CloudKernelTest, LuEquationsMatchTheirTwins) {
  for (int i = 0; i < kQueries; ++i) {
    const Inputs in = inputsOf(row(kInputs0, i), row(kInputs1, i), row(kInputs2, i));
    const glm::vec4 r0 = in.r0, r1 = in.r1;
    {
      const char* names[4] = {"Lu (3) remap", "Lu (4) SAT", "Lu (16) Li", "Lu (11) fbm"};
      expectRow(kHelpers, i,
                {luRemap(in.v, r0.x, r0.x + 0.1f + r0.y, r1.x, r1.y), luSat(in.v),
                 luLerp(r0.x, r0.y, in.v), luFbm(r0.z, r0.w, r1.x)},
                names);
    }
    const float gs = luGS(in.ph, in.cmc), gd = luGD(in.ph, in.cmc);
    {
      const char* names[4] = {"Lu (5) GSb", "Lu (6) GSt", "Lu (7) GS", "Lu (8) GDb"};
      expectRow(kHeightShape, i, {luGSb(in.ph), luGSt(in.ph, in.cmc), gs, luGDb(in.ph)}, names);
    }
    const float nstex = luNStex(in.shape);
    {
      const char* names[4] = {"Lu (9) GDt", "Lu (10) GD", "Lu (12) NStex", "Lu (13) NS"};
      expectRow(kHeightDensity, i, {luGDt(in.ph), gd, nstex, luNS(nstex, gs, in.threshold, gd)},
                names);
    }
    const float ndfbm = luNDfbm(in.detail), ndmod = luNDmod(ndfbm, in.cmc, in.ph);
    const float nsfinal = luNSfinal(nstex, gs, in.threshold);
    {
      const char* names[4] = {"Lu (14) NDfbm", "Lu (15) NDmod", "Lu (17) NSfinal", "Lu (18) d"};
      expectRow(kDetail, i, {ndfbm, ndmod, nsfinal, luDensity(nsfinal, ndmod, gd)}, names);
    }
    const glm::vec2 low = cloudTypeRange(0, in.type), mid = cloudTypeRange(1, in.type);
    {
      const char* names[4] = {"luCloudDensity", "luCloudDensity (paper threshold)",
                              "cloudHeightFraction", "tangTypeGradient"};
      expectRow(kComposed, i,
                {luCloudDensity(in.shape, in.detail, in.ph, in.cmc, in.threshold),
                 luCloudDensity(in.shape, in.detail, in.ph, in.cmc, 1.0f - in.cmc),
                 cloudHeightFraction(r0.x, low), tangTypeGradient(in.ph, in.type)},
                names);
    }
    {
      const char* names[4] = {"low bottom", "low top", "mid bottom", "mid top"};
      expectRow(kTypeRanges, i, {low, mid}, names);
    }
    const float base = tangBaseShape(in.shape, in.ph, in.type);
    const float erosion = tangErosion(ndfbm, in.ph);
    {
      const char* names[4] = {"tangBaseShape", "tangErosion", "tangDensity", "tangCloudDensity"};
      expectRow(kTang, i,
                {base, erosion, tangDensity(base, erosion, in.cmc, in.threshold),
                 tangCloudDensity(in.shape, in.detail, in.ph, in.cmc, in.type, in.threshold)},
                names);
    }
    {
      // The kernel's weight, read back: 0 and 1 are held exactly on part of the grid.
      const float w = at(kCumulusDensity, i, 3);
      EXPECT_NEAR(w, std::clamp(1.4f * r1.w - 0.2f, 0.0f, 1.0f), 1e-6) << "query " << i;
      const char* names[4] = {"cumulusGD", "cumulusNDmod", "cumulusCloudDensity", "weight"};
      expectRow(kCumulusDensity, i,
                {cumulusGD(in.ph, in.cmc, w), cumulusNDmod(ndfbm, in.cmc, in.ph, w),
                 cumulusCloudDensity(in.shape, in.detail, in.ph, in.cmc, in.threshold, w), w},
                names);
      // Weight 0 is Lu's own density.
      if (w == 0.0f) {
        EXPECT_EQ(cumulusCloudDensity(in.shape, in.detail, in.ph, in.cmc, in.threshold, w),
                  luCloudDensity(in.shape, in.detail, in.ph, in.cmc, in.threshold));
      }
    }
  }
  printWorst("density");
}

TEST_F(CloudKernelTest, LuDensityIsNonZeroOnPartOfTheGrid) {
  // A grid where every density came out 0 would match any twin: make sure it does not.
  int inside = 0, tang = 0;
  for (int i = 0; i < kQueries; ++i) {
    inside += at(kComposed, i, 0) > 0.0f;
    tang += at(kTang, i, 3) > 0.0f;
  }
  EXPECT_GT(inside, kQueries / 10);
  EXPECT_GT(tang, kQueries / 10);
  int cumulus = 0;
  for (int i = 0; i < kQueries; ++i)
    cumulus += at(kCumulusDensity, i, 2) > 0.0f && at(kCumulusDensity, i, 3) > 0.0f;
  EXPECT_GT(cumulus, kQueries / 10);
}

TEST_F(CloudKernelTest, LightingMatchesItsTwin) {
  for (int i = 0; i < kQueries; ++i) {
    const glm::vec4 r0 = row(kInputs0, i), r1 = row(kInputs1, i), r2 = row(kInputs2, i);
    const float b = 0.001f + 0.1f * r0.x, ds = 50.0f * r0.y, dsClamp = 50.0f * r0.z;
    const float cosTheta = 2.0f * r0.w - 1.0f;
    const float g = 1.98f * r1.x - 0.99f, gBack = -0.99f * r1.y, backWeight = r1.z;
    {
      // HG near g = +-0.99 divides by (1 + g^2 - 2 g cos)^1.5 ~ 1e-4: a few ulps of cosTheta
      // move it by 1e-4 relative.
      const char* names[4] = {"Lu (21) E", "Lu (22) Ec", "Lu (23) HG", "dual-lobe HG"};
      expectRow(kPhase, i,
                {beerLambert(b, ds), beerClamped(b, ds, dsClamp), henyeyGreenstein(cosTheta, g),
                 dualLobeHG(cosTheta, g, gBack, backWeight)},
                names, 2e-4);
    }
    const float x = at(kAmbientScalars, i, 2), a = at(kAmbientScalars, i, 3);
    {
      const char* names[4] = {"Ei", "slabAmbient", "x", "a"};
      expectRow(kAmbientScalars, i, {expIntegralEi(x), slabAmbient(a), x, a}, names);
    }
    const float sigmaT = at(kAmbient, i, 3);
    {
      const char* names[4] = {"ambient r", "ambient g", "ambient b", "sigmaT"};
      const glm::vec3 amb =
          cloudAmbient(glm::vec3(r0), glm::vec3(r1), sigmaT, 2000.0f * r2.w, 2000.0f * r0.w);
      expectRow(kAmbient, i, {amb, sigmaT}, names);
    }
    const float tau = 10.0f * r0.x, tauClamp = 10.0f * r0.y;
    {
      const char* names[4] = {"in-scatter hg 1", "in-scatter dual 1", "in-scatter hg 4",
                              "in-scatter dual 3"};
      expectRow(kInScatter, i,
                {cloudInScatter(tau, tauClamp, cosTheta, g, gBack, backWeight, 0, 1),
                 cloudInScatter(tau, tauClamp, cosTheta, g, gBack, backWeight, 1, 1),
                 cloudInScatter(tau, tauClamp, cosTheta, g, gBack, backWeight, 0, 4),
                 cloudInScatter(tau, tauClamp, cosTheta, g, gBack, backWeight, 1, 3)},
                names, 2e-4);
    }
    {
      const float tauD = 100.0f * r2.x * r2.x, gD = -0.5f + 1.4f * r1.y, strength = 3.0f * r1.z;
      const float dEdge = -0.1f + 1.3f * r2.y, kEdge = 1.0f + 8.0f * r0.z;
      const float typeD = -0.1f + 1.2f * r0.y;
      const char* names[4] = {"diffuseTransmittance", "cloudDiffuseInScatter", "cloudEdgeDensity",
                              "cloudDiffusionLeak"};
      expectRow(kDiffusion, i,
                {diffuseTransmittance(tauD, gD), cloudDiffuseInScatter(tauD, gD, strength),
                 cloudEdgeDensity(dEdge, kEdge), cloudDiffusionLeak(typeD)},
                names);
      const float ambientSigma = at(kAmbient, i, 3);
      const char* ambientNames[4] = {"cloudAmbientDiffuse r", "cloudAmbientDiffuse g",
                                     "cloudAmbientDiffuse b", "cloudTypeTexture"};
      expectRow(kAmbientDiffuse, i,
                {cloudAmbientDiffuse(glm::vec3(r0), glm::vec3(r0.z, r0.x, r0.y) * r1.w, glm::vec3(r1),
                                     glm::vec3(r1.z, r1.x, r1.y) * (1.0f - r1.w), ambientSigma,
                                     2000.0f * r2.w, 2000.0f * r0.w, 10.0f * r2.x, gD, 1.5f * r2.z),
                 cloudTypeTexture(typeD)},
                ambientNames, 2e-4);
      const char* rollNames[4] = {"cloudRollWeight low", "cloudRollWeight mid",
                                  "cloudPhaseSkyLight", "cloudFarExtinction"};
      expectRow(kRollWeight, i,
                {cloudRollWeight(0, typeD), cloudRollWeight(1, typeD),
                 cloudPhaseSkyLight(glm::vec3(r0) - 0.5f, 10.0f * r2.x, r1.w).x,
                 cloudFarExtinction(0.02f * r1.x, 1.1f * r2.y, 50.0f + 1000.0f * r0.w)},
                rollNames);
      const glm::vec4 shape(r0.z, r0.w, r1.x, r1.y);
      const glm::vec4 cuShape =
          cumulusShape(shape, glm::vec4(r1.z, r1.w, r2.x, r2.y), glm::vec4(r2.z, r2.w, r0.x, r0.y),
                       0.3f + 0.4f * r1.y, r2.w);
      const char* shapeNames[4] = {"cloudCumulusWeight", "cumulusOutline", "cumulusShape r",
                                   "cumulusShape g"};
      expectRow(kCumulusShape, i,
                {cloudCumulusWeight(typeD), cumulusOutline(r0.x, r0.z, r1.x, 1.2f * r1.y - 0.6f),
                 cuShape.r, cuShape.g},
                shapeNames);
    }
    const float stepSigma = at(kIntegrateInputs, i, 0), dt = at(kIntegrateInputs, i, 1);
    {
      const glm::vec3 S(r0.w, r1.w, r2.w);
      const char* names[4] = {"integrateStep r", "integrateStep g", "integrateStep b", "Riemann"};
      expectRow(kIntegrate, i, {integrateStep(S, stepSigma, dt), integrateStepRiemann(S, dt).x},
                names);
    }
    const int n = 1 + i % 8, step = (i / 8) % (n + 1);
    const float distance = 100.0f + 2000.0f * r1.x;
    EXPECT_NEAR(at(kIntegrateInputs, i, 2), lightMarchReach(distance), 1e-5 * distance);
    {
      const char* names[4] = {"lightStepStart", "lightStepLength", "lightLongStepDistance",
                              "lightLongStepLength"};
      expectRow(kSchedule, i,
                {lightStepStart(step, n, distance), lightStepLength(step, n, distance),
                 lightLongStepDistance(distance), lightLongStepLength(distance)},
                names);
    }
  }
  printWorst("lighting");
}

TEST_F(CloudKernelTest, ExponentialIntegralMatchesTabulatedValues) {
  // Ei(x) to 15 digits (mpmath), at the points the kernel's first queries take; E2 = slabAmbient.
  const double x[8] = {-1.0, -0.1, -5.0, -1e-4, -60.0, -1.5, -0.5, -20.0};
  const double ei[8] = {-0.21938393439552,  -1.82292395841939,     -0.00114829559127533,
                        -8.6332247045747,   -1.43586756568126e-28, -0.100019582406633,
                        -0.559773594776161, -9.83552529064988e-11};
  const double e2[8] = {0.148495506775922, 0.722545022194021,   0.000996469042708838,
                        0.999036682529376, 1.4130536860898e-28, 0.0731007865384808,
                        0.326643862324553, 9.40485643085815e-11};
  double worst = 0;
  for (int i = 0; i < 8; ++i) {
    ASSERT_EQ(at(kAmbientScalars, i, 2), float(x[i]));
    worst = std::max(worst, std::abs(at(kAmbientScalars, i, 0) / ei[i] - 1.0));
    // The stated accuracy: 1e-4 relative over [-60, -1e-4] (the GPU's exp and log included).
    EXPECT_NEAR(at(kAmbientScalars, i, 0), ei[i], 1e-4 * std::abs(ei[i])) << "Ei(" << x[i] << ")";
    // E2 = e^a - a Ei(a) cancels to 1e-6 of e^a at large |a|: 1e-4 relative still holds to 20,
    // and at 60 both are 1e-28 (nothing a renderer could see).
    const double tolerance = x[i] < -30 ? 1e-29 : 1e-4 * e2[i];
    EXPECT_NEAR(at(kAmbientScalars, i, 1), e2[i], tolerance) << "slabAmbient(" << x[i] << ")";
  }
  std::cout << "Ei on the GPU: worst relative error " << worst << " at the tabulated points\n";
}

TEST_F(CloudKernelTest, OneOctaveOfInScatteringIsLu22Times23) {
  for (int i = 0; i < kQueries; ++i) {
    const glm::vec4 r0 = row(kInputs0, i), r1 = row(kInputs1, i);
    const float cosTheta = 2.0f * r0.w - 1.0f;
    const float g = 1.98f * r1.x - 0.99f, gBack = -0.99f * r1.y, backWeight = r1.z;
    const float tau = 10.0f * r0.x, tauClamp = 10.0f * r0.y;
    // Lu (22) with b = 1 on optical depths, times Lu (23).
    const float hg = beerClamped(1.0f, tau, tauClamp) * henyeyGreenstein(cosTheta, g);
    const float dual =
        beerClamped(1.0f, tau, tauClamp) * dualLobeHG(cosTheta, g, gBack, backWeight);
    EXPECT_NEAR(at(kInScatter, i, 0), hg, kAbs + 2e-4 * hg) << "query " << i;
    EXPECT_NEAR(at(kInScatter, i, 1), dual, kAbs + 2e-4 * dual) << "query " << i;
    // More octaves only add light.
    EXPECT_GE(at(kInScatter, i, 2), at(kInScatter, i, 0)) << "query " << i;
  }
}

TEST_F(CloudKernelTest, LightMarchMatchesAnalyticIntegrals) {
  double worstSlab = 0;
  for (int i = 0; i < kQueries; ++i) {
    const glm::vec4 light = row(kMarchLight, i), point = row(kMarchPoint, i);
    const glm::vec3 L(light), p(point);
    const float distance = light.w, slabTop = at(kMarch, i, 3);
    const int n = int(point.w);
    // The short steps, the long step and the far step (2 distance in two parts).
    const double reach = lightMarchReach(distance) + 2.0 * double(distance);
    ASSERT_NEAR(reach, 7.0 * double(distance), 1e-6 * reach);
    // Constant 0.7 and the linear ramp 0.3 + 0.0005 z: the midpoint rule is exact for both.
    const double constant = 0.7 * reach;
    const double ramp = (0.3 + 0.0005 * p.z) * reach + 0.0005 * L.z * reach * reach / 2;
    EXPECT_NEAR(at(kMarch, i, 0), constant, 1e-5 * constant) << "constant, query " << i;
    EXPECT_NEAR(at(kMarch, i, 1), ramp, 1e-5 * ramp) << "ramp, query " << i;
    // The slab: 1 up to where the ray leaves it. The midpoint rule errs by at most the length
    // of the step the edge falls in.
    const double edge = std::min(reach, (double(slabTop) - p.z) / L.z);
    double bound = edge > lightMarchReach(distance) ? double(distance)  // a far part
                                                    : lightLongStepLength(distance);
    for (int k = 0; k < n; ++k)
      if (edge >= lightStepStart(k, n, distance) && edge <= lightStepStart(k + 1, n, distance))
        bound = lightStepLength(k, n, distance);
    const double slab = at(kMarch, i, 2);
    EXPECT_LE(std::abs(slab - edge), 0.5 * bound + 1e-3 * reach) << "slab, query " << i;
    worstSlab = std::max(worstSlab, std::abs(slab - edge) / reach);
    // And the twin, on the same densities.
    LightPath path;
    path.origin = p;
    path.direction = L;
    path.distance = distance;
    path.steps = path.nearSteps = n;
    path.longEnd = lightMarchReach(distance);
    path.longParts = 3;
    path.farEnd = path.longEnd + 2.0f * distance;
    path.farParts = 2;
    const auto twin = [&](std::function<float(glm::vec3)> density) {
      return lightMarchDensity(path, [&](glm::vec3 q, float, int) { return density(q); });
    };
    EXPECT_NEAR(at(kMarch, i, 0), twin([](glm::vec3) { return 0.7f; }), 1e-5 * constant);
    EXPECT_NEAR(at(kMarch, i, 1), twin([](glm::vec3 q) { return 0.3f + 0.0005f * q.z; }),
                1e-5 * ramp);
    EXPECT_NEAR(slab, twin([&](glm::vec3 q) { return q.z < slabTop ? 1.0f : 0.0f; }), 1e-5 * reach);
    // Split where the path leaves the first cloud: the slab is all its own (nothing beyond);
    // with a second cloud past a gap of 2 distance along the path (longer than any step, so
    // some sample falls in it), the own part is the slab's and the second cloud is beyond.
    // And the twin's split on the same densities.
    const glm::vec4 split = row(kMarchSplit, i);
    EXPECT_NEAR(split.x, slab, 1e-5 * reach) << "slab's own, query " << i;
    EXPECT_EQ(split.y, 0.0f) << "slab's beyond, query " << i;
    EXPECT_NEAR(split.z, slab, 1e-5 * reach) << "gapped slab's own, query " << i;
    const float cloudBase = slabTop + 2.0f * distance * L.z;
    const LightDepth gapped = lightMarchDepth(path, [&](glm::vec3 q, float, int) {
      if (q.z >= cloudBase) return 0.5f;
      return q.z < slabTop ? 1.0f : 0.0f;
    });
    EXPECT_NEAR(split.z, gapped.own, 1e-5 * reach) << "query " << i;
    EXPECT_NEAR(split.w, gapped.beyond, 1e-5 * reach) << "query " << i;
    // The second cloud, from where the path enters it to the march's end, half as dense.
    const double into = std::max(0.0, reach - (double(cloudBase) - p.z) / L.z);
    EXPECT_NEAR(split.w, 0.5 * into, 0.5 * double(distance) + 1e-3 * reach) << "query " << i;
  }
  std::cout << "light march, slab: worst error " << worstSlab << " of the march length\n";
}

TEST_F(CloudKernelTest, EnergyConservingStepIsExactForAnyStepLength) {
  int riemannChecked = 0;
  for (int i = 0; i < kQueries; ++i) {
    const glm::vec4 e = row(kEnergy, i);
    const double conserving = e.x, riemann = e.y, T = e.z, sigmaDt = e.w;
    // Albedo 1 and unit light: what is not transmitted is scattered toward the eye.
    EXPECT_NEAR(conserving, 1.0, 1e-5) << "sigmaT dt " << sigmaDt << ", query " << i;
    // Riemann overshoots by sigmaT dt / (1 - exp(-sigmaT dt)) - 1 (about sigmaT dt / 2) of the
    // scattered part.
    if (sigmaDt >= 0.5) {
      const double excess = sigmaDt / (1.0 - std::exp(-sigmaDt)) - 1.0;
      EXPECT_NEAR(riemann - 1.0, excess * (1.0 - T), 1e-4) << "query " << i;
      EXPECT_GT(riemann - 1.0, 0.2 * (1.0 - T));
      ++riemannChecked;
    }
  }
  EXPECT_GT(riemannChecked, 10);
}

}  // namespace
TEST_F(CloudKernelTest, ALitFaceKeepsTheTwoStreamReflectanceOfTheCloudBehindIt) {
  // diffuseBehindShare (cloud_lighting.glsl) against the two-stream solution for a
  // conservative slab of optical depth T (Bohren & Clothiaux 2006, 6.3): the lit face keeps the
  // reflectance cT / (1 + cT), c = 3/4 (1 - g), of a thick slab's diffuse light, the far face
  // all of it (diffuseTransmittance already dims it), and linearly between; a cloud still
  // there at the probe's end counts as thick.
  int thin = 0;
  for (int i = 0; i < kQueries; ++i) {
    const glm::vec4 r0 = row(kInputs0, i), r1 = row(kInputs1, i), r2 = row(kInputs2, i);
    const double tau = 100.0 * r2.x * r2.x, behind = 100.0 * r0.x * r0.x;
    const double g = -0.5 + 1.4 * r1.y, c = 0.75 * (1.0 - g);
    const auto reflectance = [&](double t) { return c * t / (1.0 + c * t); };
    const double total = tau + behind;
    const double inside =
        total > 0.0 ? reflectance(total) + (1.0 - reflectance(total)) * tau / total : 1.0;
    const double litFace = behind > 0.0 ? reflectance(behind) : 1.0;
    const char* names[4] = {"inside", "lit face", "far face", "thick"};
    expectRow(kBehindShare, i,
              glm::vec4(float(inside), float(litFace), 1.0f, float(reflectance(1.0e6))), names,
              2e-4);
    thin += behind > 0.0 && reflectance(behind) < 0.5;
  }
  EXPECT_GT(thin, 10) << "the grid holds clouds thin enough to lose half their light";
}

}  // namespace sky::test
