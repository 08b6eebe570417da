#pragma once
// The weather map of a scene at any instant of its time. The one place that decides how the
// map changes with time: the forecast's steps (interpolated), weather.time, advection by the
// file's wind or the scene's (Kozlov section 5) and the cellular automaton (weather.evolution
// ca, Liu et al. 2015). The renderer and `skyrender weather` both take their maps from here.
// See docs/weather.md, "Weather that moves".
#include <cstdint>
#include <optional>
#include <string>

#include <glm/vec2.hpp>

#include "engine/scene/scene.h"
#include "engine/weather/cloud_automaton.h"
#include "engine/weather/weather_fields.h"
#include "engine/weather/weather_map.h"

namespace sky {

// The instant (Unix seconds) the weather map shows in a frame at `frame`: weather.time moved
// on by the frame's time since the scene's start when weather.time is set, else the frame's.
double weatherTimeUnix(const WeatherInputs& in, const IsoTime& frame);

class WeatherSource {
public:
  // The map for `in` in the frame at `frame`. Rebuilt only when something it depends on
  // changed: the weather settings (and the scene's wind with advection "wind": the same wind
  // that moves the cloud noise, so cells and their detail move as one), the input files
  // (size, modification time), and the time when the map moves with it. Forecast files are
  // read once. BadInput naming weather.<key> for bad settings or files.
  // The map's region is weather.region, or else (weather_region.h mapRegion) the square around
  // the camera, clipped to the forecast's data; with setWholeDataRegion(true) a forecast
  // without weather.region shows its whole grid (skyrender weather).
  const WeatherMap& map(const WeatherInputs& in, const IsoTime& frame);
  void setWholeDataRegion(bool whole) { mWholeData = whole; }

  // The forecast of source "file" as read by the last map() (nullptr for other sources).
  const WeatherFields* fields() const { return mFields ? &*mFields : nullptr; }
  // How many maps map() has built (a cache hit builds none).
  uint64_t revision() const { return mRevision; }
  // The automaton's work in the last map() that built a map with evolution "ca".
  const CloudAutomaton::Stats& automatonStats() const { return mAutomaton.lastStats(); }

private:
  // The map at `timeUnix` before evolution: the forecast interpolated or carried, or the
  // procedural/image map carried by the scene's wind.
  WeatherMap moved(const WeatherInputs& in, double timeUnix);
  // evolution "ca": the automaton's window around `timeUnix` (the forecast steps that bracket
  // it, else automatonWindow) and its work on `map`. `signature`: the map's, without the time.
  void evolve(const WeatherInputs& in, const std::string& signature, double timeUnix,
              WeatherMap& map);

  bool mWholeData = false;
  WeatherRegion mRegion;      // of the last map()
  WeatherRegion mDataRegion;  // the extent of mFields' grid
  std::optional<WeatherFields> mFields;
  std::string mFieldsStamp;
  std::optional<WeatherMap> mStill;  // procedural/image map, before any advection
  std::string mStillSignature;
  std::optional<WeatherMap> mMap;
  std::string mMapSignature;
  std::optional<WeatherMap> mEnds[2];  // the maps at the automaton window's ends
  std::string mEndsSignature;
  CloudAutomaton mAutomaton;
  uint64_t mRevision = 0;
};

}  // namespace sky
