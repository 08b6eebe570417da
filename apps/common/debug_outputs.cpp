#include "apps/common/debug_outputs.h"

#include <algorithm>
#include <cstdio>

#include "engine/core/error.h"
#include "apps/common/debug_view.h"
#include "engine/gpu/image.h"

namespace sky {
namespace {

// The debug outputs' names before the registry (before issue 17), for scripts that use them.
const std::map<std::string, std::string>& formerNames() {
  static const std::map<std::string, std::string> names = {
      {"coefficients", "high_cloud_coefficients"},
      {"normals", "high_cloud_normals"},
      {"transmittance_lut", "atmosphere_transmittance"},
      {"multiscattering_lut", "atmosphere_multiscattering"},
      {"sky_view_sun_lut", "atmosphere_sky_view_sun"},
      {"sky_view_moon_lut", "atmosphere_sky_view_moon"},
      {"aerial_perspective", "atmosphere_aerial_perspective"},
  };
  return names;
}

}  // namespace

DebugRequest parseDebugOutputs(const std::vector<std::string>& values) {
  DebugRequest r;
  for (const std::string& v : values) {
    size_t start = 0;
    while (start <= v.size()) {
      size_t comma = v.find(',', start);
      if (comma == std::string::npos) comma = v.size();
      const std::string name = v.substr(start, comma - start);
      start = comma + 1;
      if (name == "list") {
        r.list = true;
        continue;
      }
      const auto former = formerNames().find(name);
      const std::string graphName = former != formerNames().end() ? former->second : name;
      if (std::find(r.names.begin(), r.names.end(), graphName) != r.names.end()) continue;
      r.names.push_back(graphName);
      r.asked[graphName] = name;
    }
  }
  return r;
}

void debugOutputError(const UnknownImageName& e, const DebugRequest& request,
                      const std::string& option) {
  const auto asked = request.asked.find(e.name());
  std::string valid;
  for (const std::string& k : e.known()) valid += (valid.empty() ? "" : ", ") + k;
  inputError(option + " " + (asked != request.asked.end() ? asked->second : e.name()) +
             ": the frame of this scene has no such image (valid: " + valid + ")");
}

std::string debugImageTable(const std::vector<DebugImageInfo>& images) {
  size_t nameWidth = 4, passWidth = 4;
  for (const DebugImageInfo& i : images) {
    nameWidth = std::max(nameWidth, i.name.size());
    passWidth = std::max(passWidth, i.pass.empty() ? 8 : i.pass.size());
  }
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line, "%-*s  %-*s  %-7s  %-13s  %s\n", int(nameWidth), "name",
                int(passWidth), "pass", "view", "size", "holds");
  out += line;
  for (const DebugImageInfo& i : images) {
    std::string size = std::to_string(i.width) + "x" + std::to_string(i.height);
    if (i.depth > 1) size += "x" + std::to_string(i.depth);
    std::snprintf(line, sizeof line, "%-*s  %-*s  %-7s  %-13s  ", int(nameWidth), i.name.c_str(),
                  int(passWidth), i.pass.empty() ? "imported" : i.pass.c_str(),
                  debugViewName(i.view), size.c_str());
    out += line + i.about + "\n";
  }
  return out;
}

void packDebugLayers(RenderedFrame& frame) {
  std::vector<DebugImage> rest;
  for (DebugImage& d : frame.debug) {
    if (d.image.width != frame.image.width || d.image.height != frame.image.height ||
        d.info.depth > 1) {
      rest.push_back(std::move(d));
      continue;
    }
    ImageLayer layer = std::move(d.image.layers.at(0));
    layer.name = "debug." + d.info.name;
    // FLOAT: debug images hold depths in metres and radiance by moonlight, past half's range.
    layer.fullFloat = true;
    frame.image.layers.push_back(std::move(layer));
  }
  frame.debug = std::move(rest);
}

void nameDebugImagesAsAsked(RenderedFrame& frame, const DebugRequest& request) {
  for (DebugImage& d : frame.debug) {
    const auto asked = request.asked.find(d.info.name);
    if (asked != request.asked.end()) d.info.name = asked->second;
  }
}

}  // namespace sky
