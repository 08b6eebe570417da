#pragma once
// Writes a rendered frame as STEM.exr (scene-linear, multi-layer), STEM.png (display-referred
// through the OCIO display/view) and STEM.json (settings, lighting, per-pass GPU ms, device)
// and STEM.<name>.exr per requested debug image — all or none: each goes to a temporary
// file first and they are renamed together.
// STEM is output.name for a single frame, output.name_0001 ... for a time-lapse.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/render/exposure.h"
#include "engine/render/renderer.h"

namespace sky {

class OcioOutput;

struct RenderFiles {
  std::filesystem::path exr, png, report;
  std::vector<std::filesystem::path> debug;    // STEM.<name>.exr per debug image
  std::optional<std::filesystem::path> graph;  // --dump-graph
};

// Where frame `index` (0-based) of `count` goes: NAME for an instant, NAME_0001 (at least
// four digits, more when the count needs them) for a time range, even one of a single frame
// (START = END): a script that renders ranges finds the same names whatever their length.
std::string frameStem(const std::string& name, int64_t index, int64_t count, bool range);

// `dir` must exist. `exposure` is the frame's (ExposureMeter): the PNG is exposed by it, the
// report and the EXR's "skylayers:exposure_ev" attribute say what it was. `graphPath`, when
// given, also receives the compiled graph (Graphviz).
RenderFiles writeRenderFiles(const std::filesystem::path& dir, const std::string& stem,
                             const Scene& scene, const RenderedFrame& frame,
                             const FrameExposure& exposure, const OcioOutput& ocio,
                             const std::string& deviceName,
                             const std::optional<std::filesystem::path>& graphPath = std::nullopt);

// The render report, STEM.json's content (docs/outputs.md): the settings, the lighting, each
// pass's GPU ms, the first frame's costs, the exposure, the caches. `debugFiles` names the
// debug images' files written beside it.
nlohmann::ordered_json renderReport(const Scene& scene, const RenderedFrame& frame,
                                    const FrameExposure& exposure, const OcioOutput& ocio,
                                    const std::string& deviceName,
                                    const std::vector<std::string>& debugFiles = {});

// The display-referred RGBA pixels of the main layer: the night look (output.night_look) on
// the physical values, then the exposure and the OCIO view.
std::vector<float> displayPixels(const RenderedFrame& frame, const Scene& scene,
                                 const FrameExposure& exposure, const OcioOutput& ocio);

}  // namespace sky
