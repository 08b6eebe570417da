#pragma once
// Writes a rendered frame as NAME.exr (scene-linear, multi-layer), NAME.png (display-referred
// through the OCIO display/view) and NAME.json (settings, per-pass GPU ms, device) — all
// three or none: each goes to a temporary file first and they are renamed together.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/render/renderer.h"

namespace sky {

class OcioOutput;

struct RenderFiles {
  std::filesystem::path exr, png, report;
  std::optional<std::filesystem::path> graph;  // --dump-graph
};

// `dir` must exist. `graphPath`, when given, also receives the compiled graph (Graphviz).
RenderFiles writeRenderFiles(const std::filesystem::path& dir, const Scene& scene,
                             const RenderedFrame& frame, const OcioOutput& ocio,
                             const std::string& deviceName,
                             const std::optional<std::filesystem::path>& graphPath = std::nullopt);

// The display-referred RGBA pixels of the main layer (exposure and OCIO view applied).
std::vector<float> displayPixels(const RenderedFrame& frame, const Scene& scene,
                                 const OcioOutput& ocio);

}  // namespace sky
