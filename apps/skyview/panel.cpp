#include "panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/color/ocio_output.h"

namespace sky::view {

namespace {

// A combo over a scene choice's name table: the file's names, in the file's order.
template <SceneEnum E>
bool enumCombo(const char* key, E& value) {
  bool changed = false;
  if (ImGui::BeginCombo(key, enumName(value))) {
    for (const EnumName<E>& n : enumNames(E{})) {
      const bool selected = n.value == value;
      if (ImGui::Selectable(n.name, selected) && !selected) {
        value = n.value;
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  return changed;
}

bool textCombo(const char* key, std::string& value, const std::vector<std::string>& choices) {
  bool changed = false;
  if (ImGui::BeginCombo(key, value.c_str())) {
    for (const std::string& c : choices) {
      const bool selected = c == value;
      if (ImGui::Selectable(c.c_str(), selected) && !selected) {
        value = c;
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  return changed;
}

bool slider(const char* key, double& value, double min, double max, const char* format = "%.3f",
            ImGuiSliderFlags flags = 0) {
  return ImGui::SliderScalar(key, ImGuiDataType_Double, &value, &min, &max, format, flags);
}

// Two short lines: they must fit a 640-pixel window.
constexpr const char* kHelp =
    "drag: look  WASD: move  Q/E: down/up  [ ]: time  , .: date  Space: play\n"
    "F12: screenshot  Ctrl+S: save scene  Tab/V: debug view  F1: panel  Esc: quit";

}  // namespace

double localHours(const IsoTime& time) {
  const double local =
      static_cast<double>(time.unixSeconds + time.offsetMinutes * 60LL) + time.subsecond;
  double h = std::fmod(local / 3600.0, 24.0);
  return h < 0 ? h + 24.0 : h;
}

IsoTime withLocalHours(const IsoTime& time, double hours) {
  return time.plusSeconds((hours - localHours(time)) * 3600.0);
}

void beginOverlay(const char* id, float x, float y, float pivotX, float pivotY) {
  ImGui::SetNextWindowPos(ImVec2(x, y), ImGuiCond_Always, ImVec2(pivotX, pivotY));
  ImGui::SetNextWindowBgAlpha(0.45f);
  ImGui::Begin(id, nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs);
}

PanelActions drawPanel(Scene& scene, PanelState& state, const PanelInfo& info,
                       const OcioOutput& ocio, bool visible) {
  PanelActions a;
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  // Messages and the help line sit on the frame itself, panel or not.
  beginOverlay("##status", viewport->WorkPos.x + 4, viewport->WorkPos.y + viewport->WorkSize.y - 4,
               0, 1);
  for (const std::string& e : info.errors)
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", e.c_str());
  if (!info.status.empty()) ImGui::TextUnformatted(info.status.c_str());
  ImGui::TextUnformatted(kHelp);
  ImGui::End();
  if (!visible) return a;

  // Per-pass GPU time, top right, small enough to leave the sky visible.
  beginOverlay("##passes", viewport->WorkPos.x + viewport->WorkSize.x - 4, viewport->WorkPos.y + 4,
               1, 0);
  ImGui::Text("%ux%u  %.0f ms  %.1f fps", info.renderWidth, info.renderHeight, info.renderMs,
              info.fps);
  double total = 0.0;
  for (const PassTiming& p : info.passes) {
    ImGui::Text("%-24s %7.2f", p.name.c_str(), p.gpuMs);
    total += p.gpuMs;
  }
  ImGui::Text("%-24s %7.2f", "GPU ms total", total);
  ImGui::End();

  // The panel: left, no taller than the window less the help lines.
  ImGui::SetNextWindowPos(ImVec2(viewport->WorkPos.x + 4, viewport->WorkPos.y + 4),
                          ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSizeConstraints(ImVec2(200, 60),
                                      ImVec2(420, std::max(60.0f, viewport->WorkSize.y - 64)));
  ImGui::SetNextWindowSize(ImVec2(330, viewport->WorkSize.y * 0.75f), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.75f);
  if (!ImGui::Begin("skyview")) {
    ImGui::End();
    return a;
  }
  a.screenshot = ImGui::Button("Screenshot (F12)");
  ImGui::SameLine();
  a.saveScene = ImGui::Button("Save scene (Ctrl+S)");
  ImGui::PushItemWidth(140);

  if (ImGui::CollapsingHeader("time", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::TextUnformatted(scene.time.start.format().c_str());
    double hours = localHours(scene.time.start);
    if (slider("time (hour of day)", hours, 0.0, 24.0, "%.2f h")) {
      scene.time.start = withLocalHours(scene.time.start, hours);
      a.sceneChanged = true;
    }
    if (ImGui::Button("-1 day")) {
      scene.time.start = scene.time.start.plusSeconds(-86400.0);
      a.sceneChanged = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("+1 day")) {
      scene.time.start = scene.time.start.plusSeconds(86400.0);
      a.sceneChanged = true;
    }
    ImGui::SameLine();
    ImGui::Checkbox("play (Space)", &state.playing);
    slider("speed (scene s / s)", state.speed, 1.0, 86400.0, "%.0f", ImGuiSliderFlags_Logarithmic);
  }
  if (ImGui::CollapsingHeader("clouds", ImGuiTreeNodeFlags_DefaultOpen)) {
    a.sceneChanged |= slider("weather.cover_low", scene.weather.coverLow, 0.0, 1.0, "%.2f");
    a.sceneChanged |= slider("weather.cover_mid", scene.weather.coverMid, 0.0, 1.0, "%.2f");
    a.sceneChanged |= enumCombo("weather.cloud_type", scene.weather.cloudType);
    a.sceneChanged |= enumCombo("clouds.model", scene.clouds.model);
    a.sceneChanged |= enumCombo("clouds.temporal.mode", scene.clouds.temporal.mode);
    a.sceneChanged |= slider("high_clouds.cover", scene.highClouds.cover, 0.0, 1.0, "%.2f");
    a.sceneChanged |= enumCombo("high_clouds.style", scene.highClouds.style);
  }
  if (ImGui::CollapsingHeader("sky and exposure", ImGuiTreeNodeFlags_DefaultOpen)) {
    a.sceneChanged |= enumCombo("sky.model", scene.sky.model);
    a.sceneChanged |= enumCombo("output.exposure", scene.output.exposure);
    a.sceneChanged |= slider("output.exposure_ev", scene.output.exposureEv, -10.0, 10.0, "%.2f");
    if (textCombo("output.display", scene.output.display, ocio.displays())) {
      // A view of the old display may not exist on the new one: take the new one's first.
      const std::vector<std::string> views = ocio.views(scene.output.display);
      if (!views.empty() && std::find(views.begin(), views.end(), scene.output.view) == views.end())
        scene.output.view = views.front();
      a.sceneChanged = true;
    }
    a.sceneChanged |= textCombo("output.view", scene.output.view, ocio.views(scene.output.display));
  }
  if (ImGui::CollapsingHeader("camera")) {
    a.sceneChanged |= slider("camera.heading", scene.camera.heading, 0.0, 360.0, "%.1f");
    a.sceneChanged |= slider("camera.pitch", scene.camera.pitch, -89.0, 89.0, "%.1f");
    a.sceneChanged |= slider("camera.vertical_fov", scene.camera.verticalFov, 5.0, 120.0, "%.1f");
    a.sceneChanged |= slider("camera.altitude_m", scene.camera.altitudeM, 0.0, 20000.0, "%.0f",
                             ImGuiSliderFlags_Logarithmic);
    a.sceneChanged |= slider("camera.latitude", scene.camera.latitude, -89.9, 89.9, "%.4f");
    a.sceneChanged |= slider("camera.longitude", scene.camera.longitude, -180.0, 180.0, "%.4f");
    a.sceneChanged |= enumCombo("camera.projection", scene.camera.projection);
  }
  if (slider("render scale", state.renderScale, 0.1, 1.0, "%.2f")) a.sceneChanged = true;
  ImGui::PopItemWidth();

  ImGui::End();
  return a;
}

}  // namespace sky::view
