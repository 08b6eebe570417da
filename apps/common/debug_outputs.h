#pragma once
// The apps' side of the debug view: the names a user asks for (--debug-output a,b; repeats;
// "list"), the one-line error for a name the frame lacks, the list of a frame's images, and
// the packing of debug images into the files skyrender writes.
#include <map>
#include <string>
#include <vector>

#include "engine/graph/frame_graph.h"
#include "engine/render/renderer.h"

namespace sky {

struct DebugRequest {
  std::vector<std::string> names;            // graph image names, in the order asked
  std::map<std::string, std::string> asked;  // graph name -> the name as the user wrote it
  bool list = false;                         // "list": print the frame's images and stop
};

// `values` of `option` (each "a,b" or "a"). The names the debug outputs had before every
// graph image could be asked for (transmittance_lut, coefficients, ...) still name theirs.
DebugRequest parseDebugOutputs(const std::vector<std::string>& values);

// BadInput "OPTION NAME: the frame of this scene has no such image (valid: a, b, ...)".
[[noreturn]] void debugOutputError(const UnknownImageName& e, const DebugRequest& request,
                                   const std::string& option);

// A table of the frame's images: name, the pass that writes it, view, size, what it holds.
std::string debugImageTable(const std::vector<DebugImageInfo>& images);

// Moves the debug images of the frame's own size into the frame's EXR as layers
// "debug.<name>" (channels as the image names them); the others stay in frame.debug, each
// for its own file. The images keep their order.
void packDebugLayers(RenderedFrame& frame);

// Gives each debug image the name the user asked for it by, so its file is named so.
void nameDebugImagesAsAsked(RenderedFrame& frame, const DebugRequest& request);

}  // namespace sky
