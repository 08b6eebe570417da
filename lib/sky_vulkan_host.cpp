// Sky::record: the sky, the clouds and the haze drawn into a host's own Vulkan images, with
// its depth, in its command buffer (docs/library.md, "Into the host's images").
#include "sky_impl.h"

#include "engine/render/render_files.h"

namespace skylayers {

using namespace detail;

namespace {

bool hasStencil(VkFormat f) {
  return f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

// The host's depth values as distances (shaders/common/atmosphere_composite_shared.h).
sky::shared::HostDepth depthMapping(const DepthConvention& c) {
  sky::shared::HostDepth m{};
  const auto bad = [](const std::string& why) {
    throw Error(Error::Kind::BadInput, "record: HostFrame::depthConvention: " + why);
  };
  double a = 0.0, b = 0.0;
  if (c.useProjection) {
    a = c.projection[10];
    b = c.projection[14];
    if (c.projection[11] != -1.0 || c.projection[15] != 0.0 || b == 0.0 || !std::isfinite(a) ||
        !std::isfinite(b))
      bad("the projection is not a perspective one in Vulkan's clip space (m[11] = -1, "
          "m[15] = 0, m[14] != 0)");
    // Its far end: the depth (0 or 1) whose distance b / (d + a) is the larger or infinite.
    const double z0 = a == 0.0 ? INFINITY : b / a, z1 = a == -1.0 ? INFINITY : b / (1.0 + a);
    if (!(z0 > 0.0 || z1 > 0.0)) bad("the projection puts depths 0 and 1 behind the camera");
    m.emptyDepth = (z1 > 0.0 && (z0 <= 0.0 || z1 > z0)) ? 1.0f : 0.0f;
  } else {
    const double n = c.nearM, f = c.farM;
    if (!(n > 0.0) || !std::isfinite(n) || !(f > n))
      bad("near " + std::to_string(n) + " m and far " + std::to_string(f) +
          " m: need 0 < near < far (far may be infinite)");
    const bool infinite = std::isinf(f);
    if (c.reverseZ) {
      a = infinite ? 0.0 : n / (f - n);
      b = infinite ? n : n * f / (f - n);
    } else {
      a = infinite ? -1.0 : f / (n - f);
      b = infinite ? -n : n * f / (n - f);
    }
    m.emptyDepth = c.reverseZ ? 0.0f : 1.0f;
  }
  m.depthA = static_cast<float>(a);
  m.depthB = static_cast<float>(b);
  return m;
}

}  // namespace

Frame Sky::record(const HostFrame& host) {
  return translated([&] {
    Impl& m = *mImpl;
    const auto bad = [](const std::string& why) {
      throw Error(Error::Kind::BadInput, "record: " + why);
    };
    if (!m.onHostDevice)
      bad("the Sky is on its own device; record() draws into a host's images on the host's "
          "device (DeviceOptions::vulkan)");
    if (!host.commandBuffer) bad("HostFrame::commandBuffer is VK_NULL_HANDLE");
    const HostImage& c = host.colour;
    if (!c.image) bad("HostFrame::colour.image is VK_NULL_HANDLE");
    if (c.format != VK_FORMAT_R16G16B16A16_SFLOAT && c.format != VK_FORMAT_R32G32B32A32_SFLOAT)
      bad("HostFrame::colour.format " + std::to_string(c.format) +
          ": the colour must be R16G16B16A16_SFLOAT or R32G32B32A32_SFLOAT (scene-linear)");
    if (c.width == 0 || c.height == 0) bad("HostFrame::colour has no size");
    const HostImage& d = host.depth;
    if (d.image) {
      if (d.format != VK_FORMAT_D16_UNORM && d.format != VK_FORMAT_X8_D24_UNORM_PACK32 &&
          d.format != VK_FORMAT_D32_SFLOAT && !hasStencil(d.format))
        bad("HostFrame::depth.format " + std::to_string(d.format) + " is not a depth format");
      if (d.width != c.width || d.height != c.height)
        bad("HostFrame::depth is " + std::to_string(d.width) + "x" + std::to_string(d.height) +
            ", the colour " + std::to_string(c.width) + "x" + std::to_string(c.height));
      if (m.scene.camera.projection != sky::CameraProjection::Perspective ||
          m.scene.camera.mode != sky::CameraMode::Observer)
        bad("a host's depth needs a perspective observer camera");
    }
    const sky::shared::HostDepth mapping = depthMapping(host.depthConvention);
    if (m.scene.output.width != static_cast<int>(c.width) ||
        m.scene.output.height != static_cast<int>(c.height))
      m.apply(
          {"output.width=" + std::to_string(c.width), "output.height=" + std::to_string(c.height)});

    // The last frame's views go: the host has run it (the contract above).
    m.hostColour.reset();
    m.hostDepth.reset();
    sky::ImageDesc cd;
    cd.name = "host_colour";
    cd.format = c.format;
    cd.width = c.width;
    cd.height = c.height;
    cd.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    m.hostColour.emplace(sky::PersistentImage{sky::Image::borrow(m.context, cd, c.image), {}});
    sky::HostTarget target;
    target.cmd = host.commandBuffer;
    target.colour = &*m.hostColour;
    target.colourLayout = c.layout;
    if (d.image) {
      sky::ImageDesc dd = cd;
      dd.name = "host_depth";
      dd.format = d.format;
      dd.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
      dd.view = sky::DebugView::Depth;
      dd.aspect =
          VK_IMAGE_ASPECT_DEPTH_BIT | (hasStencil(d.format) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
      m.hostDepth.emplace(sky::PersistentImage{sky::Image::borrow(m.context, dd, d.image), {}});
      target.depth = &*m.hostDepth;
      target.depthLayout = d.layout;
    }
    target.depthMapping = mapping;
    sky::RenderOptions options;
    options.host = &target;
    const sky::IsoTime& time = m.scene.time.start;
    sky::RenderedFrame rendered = m.renderer.render(m.scene, time, options);

    Frame frame;
    frame.time = time.format();
    // The scene's exposure without metering (the frame is the host's, on its GPU).
    sky::FrameExposure exposure;
    exposure.mode = m.scene.output.exposure == sky::ExposureMode::Fixed ? sky::ExposureMode::Fixed
                                                                        : sky::ExposureMode::Auto;
    exposure.ev = (exposure.mode == sky::ExposureMode::Auto ? rendered.lighting.autoExposureEv : 0.0) +
                  m.scene.output.exposureEv;
    frame.exposureEv = exposure.ev;
    frame.report =
        sky::renderReport(m.scene, rendered, exposure, m.ocio, m.context.deviceName()).dump(2);
    return frame;
  });
}

void Sky::forgetHostImages() {
  mImpl->hostColour.reset();
  mImpl->hostDepth.reset();
}

}  // namespace skylayers
