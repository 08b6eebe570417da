// The sampling functions other passes call (shaders/common/atmosphere.glsl) run in a kernel
// shader against the direct CPU reference: transmittanceToTop, transmittanceAlong (the
// ratio trick) and aerialPerspective (froxel volume + its sampling), and the aerial
// perspective froxels as stored.
#include <array>
#include <iostream>

#include "atmosphere_reference.h"
#include "atmosphere_test_util.h"
#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/pass_context.h"

namespace sky::test {
namespace {

constexpr int kQueries = 64;  // KERNEL_QUERIES in atmosphere_api_kernel.comp

struct Query {
  glm::dvec3 V{0, 0, 1};
  double distance = 0;  // km
  double r = 0, mu = 1;
  double u = 0.5, v = 0.5;
};

// Queries spread over the domain with low-discrepancy sequences (golden ratios).
std::array<Query, kQueries> makeQueries(const shared::AtmosphereParams& p,
                                        const shared::ViewState& view) {
  std::array<Query, kQueries> q;
  const double ground = p.radii.x, top = p.radii.y;
  for (int i = 0; i < kQueries; ++i) {
    const double a = std::fmod(0.5 + i * 0.6180339887, 1.0);
    const double b = std::fmod(0.5 + i * 0.7548776662, 1.0);
    const double c = std::fmod(0.5 + i * 0.5698402910, 1.0);
    Query& x = q[static_cast<size_t>(i)];
    // transmittanceToTop: any altitude, directions from 20 degrees below the horizontal up.
    x.r = ground + 0.001 + (top - ground - 0.002) * a * a;
    x.mu = -0.34 + 1.34 * b;
    // aerialPerspective: a screen position and a distance (0..40 km, past the last slice).
    x.u = 0.02 + 0.96 * b;
    x.v = 0.02 + 0.96 * c;
    x.distance = 40.0 * a * a;
    // transmittanceAlong: the same ray as the AP query.
    x.V = viewRay(view, x.u, x.v);
  }
  return q;
}

class AtmosphereApiTest : public AtmosphereTest {
protected:
  // Runs the kernel on this frame's LUTs; returns the 64x3 results image.
  ReadbackImage runKernel(const AtmosphereLuts::Frame& frame, const std::array<Query, kQueries>& q,
                          ReadbackImage* ap) {
    ShaderCompiler compiler(shaderDir(), std::nullopt);
    CompiledShader shader = compiler.compile(std::filesystem::path(SKY_ATMOSPHERE_TEST_DIR) /
                                             "atmosphere_api_kernel.comp");
    ComputePipeline pipeline(ctx(), "atmosphere_api_kernel", shader.spirv, shader.reflection);
    std::array<glm::vec4, 2 * kQueries> packed;
    for (int i = 0; i < kQueries; ++i) {
      const Query& x = q[static_cast<size_t>(i)];
      packed[2 * i] = glm::vec4(glm::vec3(x.V), x.distance);
      packed[2 * i + 1] = glm::vec4(x.r, x.mu, x.u, x.v);
    }
    FrameGraph graph(runtime());
    AtmosphereLuts::Outputs out = luts().addTo(graph, frame);
    const shared::AtmosphereParams params = luts().params();
    ImageId results;
    GraphBuilder b = graph.addPass("atmosphere_api_kernel", [&](PassContext& pc) {
      pc.dispatch(
          pipeline,
          {Binding::of(0, pc.uniform(params)),
           Binding::of(1, pc.uniform(packed.data(), sizeof packed)),
           Binding::of(2, out.transmittance, &luts().sampler()),
           Binding::of(3, out.aerialPerspective, &luts().sampler()), Binding::of(4, results)},
          1, 1);
    });
    b.read(out.transmittance, Access::SampledCompute);
    b.read(out.aerialPerspective, Access::SampledCompute);
    ImageDesc d;
    d.name = "results";
    d.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    d.width = kQueries;
    d.height = 3;
    results = b.write(b.create(d), Access::StorageWriteCompute);
    graph.requestOutput(results, "results");
    graph.requestOutput(out.aerialPerspective, "ap");
    FrameResult r = graph.execute();
    if (ap) *ap = r.output("ap");
    return r.output("results");
  }
};

AtmosphereLuts::Frame apFrame() {
  AtmosphereLuts::Frame f = sunFrame(120, 25, 800.0);
  f.view = testView(150, 5, 70, 64, 36);
  f.sunIlluminance = glm::vec3(4.0f, 4.1f, 4.2f);
  // A bright moon elsewhere in the sky, so the aerial perspective sums two lights.
  f.moonDirection = glm::vec3(enuDirection(250, 40));
  f.moonIlluminance = glm::vec3(1.0f, 0.9f, 0.8f);
  return f;
}

TEST_F(AtmosphereApiTest, TransmittanceFunctionsMatchDirectQuadrature) {
  const AtmosphereLuts::Frame frame = apFrame();
  // Params of this frame (for the query set) before the kernel adds the frame itself.
  shared::AtmosphereParams p = atmosphereParams(frame.atmosphere);
  setAtmosphereCamera(p, frame.cameraAltitudeM);
  const std::array<Query, kQueries> q = makeQueries(p, frame.view);
  const ReadbackImage res = runKernel(frame, q, nullptr);
  AtmosphereReference ref(frame.atmosphere);
  const double r0 = p.radii.z;
  double worstTop = 0, worstAlong = 0;
  for (int i = 0; i < kQueries; ++i) {
    const Query& x = q[static_cast<size_t>(i)];
    // transmittanceToTop: the direct optical depth to the top, or 0 below the horizon.
    const glm::dvec3 origin(0, 0, x.r), dir(std::sqrt(1 - x.mu * x.mu), 0, x.mu);
    const glm::dvec3 expectedTop = ref.transmittanceToLight(origin, dir);
    // transmittanceAlong: the direct optical depth from the camera over the distance (up to
    // the ground or the top).
    const glm::dvec3 camera(0, 0, r0);
    const double length = std::min(x.distance, ref.rayLength(r0, x.V.z));
    const glm::dvec3 expectedAlong = glm::exp(-ref.opticalDepth(camera, x.V, length, 512));
    for (int c = 0; c < 3; ++c) {
      // Tolerance: 1e-3 absolute plus 2 % relative. Bilinear interpolation of the LUT is
      // least accurate for rays a degree off the horizon (about 1.7 % at worst).
      const double gotTop = texel(res, i, 0, c), gotAlong = texel(res, i, 1, c);
      EXPECT_NEAR(gotTop, expectedTop[c], 1e-3 + 0.02 * expectedTop[c])
          << "query " << i << " r " << x.r << " mu " << x.mu << " channel " << c;
      EXPECT_NEAR(gotAlong, expectedAlong[c], 1e-3 + 0.02 * expectedAlong[c])
          << "query " << i << " V.z " << x.V.z << " distance " << x.distance << " channel " << c;
      worstTop = std::max(worstTop, std::abs(gotTop - expectedTop[c]));
      worstAlong = std::max(worstAlong, std::abs(gotAlong - expectedAlong[c]));
    }
  }
  std::cout << "transmittanceToTop worst abs error " << worstTop << ", transmittanceAlong "
            << worstAlong << "\n";
}

TEST_F(AtmosphereApiTest, AerialPerspectiveMatchesTheDirectReference) {
  const AtmosphereLuts::Frame frame = apFrame();
  shared::AtmosphereParams p = atmosphereParams(frame.atmosphere);
  setAtmosphereCamera(p, frame.cameraAltitudeM);
  const std::array<Query, kQueries> q = makeQueries(p, frame.view);
  ReadbackImage ap;
  const ReadbackImage res = runKernel(frame, q, &ap);
  ASSERT_EQ(ap.width, 32u);
  ASSERT_EQ(ap.depth, 32u);
  AtmosphereReference ref(frame.atmosphere);
  const double r0 = p.radii.z;
  const glm::dvec3 Ls(frame.sunDirection), Lm(frame.moonDirection);
  const glm::dvec3 Es(frame.sunIlluminance), Em(frame.moonIlluminance);
  auto expected = [&](glm::dvec3 V, double distance, double& meanT) {
    glm::dvec3 T;
    const glm::dvec3 sun = ref.inScattered(r0, V, Ls, distance, &T);
    const glm::dvec3 moon = ref.inScattered(r0, V, Lm, distance, nullptr);
    meanT = (T.r + T.g + T.b) / 3.0;
    return kPi * (sun * Es + moon * Em);
  };

  // The froxels as stored, at a few screen positions and slices. Tolerance: 3 % relative.
  double worstStored = 0;
  int checked = 0;
  for (uint32_t x : {3u, 17u, 30u})
    for (uint32_t y : {2u, 20u})
      for (uint32_t k : {0u, 4u, 15u, 31u}) {
        const double z = (k + 0.5) / 32.0;
        const glm::dvec3 V = viewRay(frame.view, (x + 0.5) / 32.0, (y + 0.5) / 32.0);
        // Past the ground the froxels only extrapolate (see the shader); nothing lies there.
        if (32.0 * z * z > ref.rayLength(r0, V.z)) continue;
        ++checked;
        double meanT;
        const glm::dvec3 want = expected(V, 32.0 * z * z, meanT);
        const glm::dvec3 got = rgb(ap, x, y, k);
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(got[c], want[c], 0.03 * want[c]) << "froxel " << x << "," << y << "," << k;
          worstStored = std::max(worstStored, std::abs(got[c] / want[c] - 1));
        }
        EXPECT_NEAR(texel(ap, x, y, 3, k), meanT, 0.003) << "froxel " << x << "," << y << "," << k;
      }

  EXPECT_GE(checked, 18) << "froxels in front of the ground";

  // aerialPerspective() anywhere: interpolated between froxels and slices. Tolerance: 8 % of
  // the value plus 1 % of the farthest slice's (linear interpolation of a curved function).
  double worstSampled = 0;
  for (int i = 0; i < kQueries; ++i) {
    const Query& x = q[static_cast<size_t>(i)];
    if (x.distance > ref.rayLength(r0, x.V.z)) continue;
    double meanT;
    const glm::dvec3 want =
        expected(x.V, std::min(x.distance, 32.0 * std::pow(31.5 / 32, 2)), meanT);
    double farT;
    const glm::dvec3 far = expected(x.V, 32.0 * std::pow(31.5 / 32, 2), farT);
    for (int c = 0; c < 3; ++c) {
      const double got = texel(res, i, 2, c);
      EXPECT_NEAR(got, want[c], 0.08 * want[c] + 0.01 * far[c])
          << "query " << i << " uv " << x.u << "," << x.v << " distance " << x.distance;
      worstSampled = std::max(worstSampled, std::abs(got - want[c]) / far[c]);
    }
    EXPECT_NEAR(texel(res, i, 2, 3), meanT, 0.01) << "query " << i;
  }
  std::cout << "aerial perspective: stored froxels worst relative error " << worstStored
            << ", sampled worst error " << worstSampled << " of the far slice\n";
}

}  // namespace
}  // namespace sky::test
