#pragma once
// The star field: every catalogue star rotated from J2000 into the camera's east-north-up
// frame, dimmed by extinction (Kasten-Young air mass), faded out just below the horizon and
// splatted bilinearly into a buffer of fixed-point flux, one uint per pixel
// (shaders/star_field.comp; layout in shaders/common/star_field_shared.h). Composites read
// it through shaders/common/star_field.glsl. Two graph passes: star_clear zeroes the
// transient buffer, star_field accumulates into it with atomics.
#include <optional>
#include <span>

#include <glm/mat3x3.hpp>

#include "engine/gpu/compute_pipeline.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/pass_context.h"
#include "engine/lighting/star_catalog.h"
#include "shaders/common/star_field_shared.h"

namespace sky {

class Context;
class ShaderCompiler;

// Bytes of the flux buffer of a width x height image: the uvec4 header, one uint per pixel.
VkDeviceSize starFluxBufferBytes(uint32_t width, uint32_t height);

// Whether any star can show in a frame: the brightest catalogue star (`brightestVmag`), its
// flux (`fluxPerVega`: LightingState night.z, a V = 0 star's illuminance) spread over one pixel
// of `pixelSolidAngleSr`, against the radiance of the sky behind it (`skyLuminance`): under
// 1/1000 of it the star is below one 8-bit code of any view, so by day the star passes are
// left out ("no star passes by day"). A camera with pixels small enough (a long lens) keeps
// them: the brightest stars do show in a telescope's daytime sky.
bool starsVisible(double brightestVmag, double fluxPerVega, double pixelSolidAngleSr,
                  double skyLuminance);

// Creates the frame's flux buffer, zeroed, with its (width, height) header.
class StarClearPass {
public:
  static constexpr const char* kName = "star_clear";
  struct Inputs {
    uint32_t width = 0, height = 0;  // the image the stars are splatted for
  };
  struct Outputs {
    BufferId flux;
  };

  // Compiles star_clear.comp (once, at start-up).
  StarClearPass(const Context& ctx, ShaderCompiler& compiler);
  // One use's data, in the frame graph (FrameGraph::add): once per view.
  struct Data {
    Inputs inputs{};
    Outputs outputs;
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  ComputePipeline mPipeline;
};

class StarFieldPass {
public:
  static constexpr const char* kName = "star_field";
  // What changes from frame to frame.
  struct Frame {
    shared::ViewState view;
    glm::mat3 j2000ToEnu{1.0f};  // rotation J2000 equatorial -> camera east-north-up
    float extinction = 0.2f;     // k: V-band magnitudes per air mass (0.2: clear, low site)
  };
  struct Inputs {
    BufferId stars;  // starBuffer() imported into this frame's graph
    BufferId flux;   // StarClearPass's output for the same image size
    Frame frame;
  };
  struct Outputs {
    BufferId flux;  // fixed-point star flux per pixel (star_field_shared.h)
  };

  // Compiles both shaders and uploads the stars (direction, 10^(-0.4 V)) once into a
  // persistent host-visible buffer. `stars` must not be empty.
  StarFieldPass(const Context& ctx, ShaderCompiler& compiler, std::span<const Star> stars);

  // Imports the star buffer, adds star_clear and star_field to `graph` and returns the
  // filled flux buffer. This pass object must outlive graph.execute().
  // With `visible` false (stars drowned in the day sky, starsVisible) it adds no pass and
  // returns none: the composite then compiles the stars out.
  std::optional<Outputs> addTo(FrameGraph& graph, const Frame& frame, bool visible = true);

  // The pieces addTo() uses, for graphs that want to place the passes themselves.
  PersistentBuffer& starBuffer() { return mStars; }
  // The V magnitude of the brightest star in the catalogue.
  double brightestVmag() const { return mBrightestVmag; }
  uint32_t starCount() const { return mStarCount; }
  // One use's data, in the frame graph (FrameGraph::add): once per view.
  struct Data {
    shared::StarFieldParams params{};
    Inputs inputs{};
    Outputs outputs;
  };
  Outputs setup(GraphBuilder& builder, const Inputs& inputs, Data& data);
  void execute(PassContext& ctx, const Data& data) const;

private:
  StarClearPass mClear;
  ComputePipeline mPipeline;
  PersistentBuffer mStars;
  uint32_t mStarCount = 0;
  double mBrightestVmag = 0.0;
};

}  // namespace sky
