#pragma once
// The settings panel (Dear ImGui): each control edits one scene key and is labelled with its
// path as the scene file writes it (weather.cover_low, sky.model, output.exposure_ev, ...),
// so what the panel shows is what a saved scene or skyrender --set would say.
#include <string>
#include <vector>

#include "engine/graph/frame_graph.h"
#include "engine/scene/scene.h"

namespace sky {
class OcioOutput;
}

namespace sky::view {

// The viewer's own state the panel shows and edits besides the scene.
struct PanelState {
  bool playing = false;      // the time-lapse runs
  double speed = 600.0;      // scene seconds per second of wall time
  double renderScale = 1.0;  // render size / framebuffer size
};

// What the panel shows without editing.
struct PanelInfo {
  uint32_t renderWidth = 0, renderHeight = 0;
  double renderMs = 0.0;  // the last render's wall time
  double fps = 0.0;
  std::vector<PassTiming> passes;   // the last render's per-pass GPU ms
  std::vector<std::string> errors;  // shader / scene / render errors, one line each
  std::string status;               // the last message (a screenshot written, ...)
};

struct PanelActions {
  bool sceneChanged = false;  // a scene key changed: render again
  bool screenshot = false;
  bool saveScene = false;
};

// Draws the panel (when `visible`), the help line and the messages; the caller has begun
// an ImGui frame.
PanelActions drawPanel(Scene& scene, PanelState& state, const PanelInfo& info,
                       const OcioOutput& ocio, bool visible);

// Begins a small translucent text box over the frame (no title, no input) whose `pivot`
// corner (0..1 each way) sits at window pixel (x, y); end it with ImGui::End().
void beginOverlay(const char* id, float x, float y, float pivotX, float pivotY);

// The local time of day (hours in the time's own zone) and the instant `hours` sets it to.
double localHours(const IsoTime& time);
IsoTime withLocalHours(const IsoTime& time, double hours);

}  // namespace sky::view
