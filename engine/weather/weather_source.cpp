#include "engine/weather/weather_source.h"

#include <cmath>
#include <filesystem>
#include <sstream>
#include <vector>

#include "engine/core/error.h"
#include "engine/weather/cloud_layers_from_fields.h"
#include "engine/weather/weather_region.h"

namespace sky {
namespace {

// A file as the scene names it: path, size and modification time, so an edited file is read
// again.
std::string fileStamp(const std::filesystem::path& file) {
  std::error_code ec;
  std::ostringstream s;
  s << file.string() << '|' << std::filesystem::file_size(file, ec) << '|'
    << std::filesystem::last_write_time(file, ec).time_since_epoch().count();
  return s.str();
}

// The stamps of every file weather.file names (a pattern's matches included), so a new,
// removed or edited step file is noticed.
std::string filesStamp(const WeatherInputs& in) {
  std::string stamp;
  for (const std::filesystem::path& f : weatherFiles(in)) stamp += fileStamp(f) + ';';
  return stamp;
}

// What the map depends on besides the time and the forecast file: every weather setting and
// the region it covers.
std::string settingsSignature(const WeatherInputs& in, const WeatherRegion& region) {
  const WeatherSettings& w = in.settings;
  std::ostringstream s;
  s.precision(17);
  s << enumName(w.source) << '|' << region.lat[0] << ',' << region.lat[1] << ',' << region.lon[0]
    << ',' << region.lon[1] << '|' << w.coverLow << '|' << w.coverMid << '|' << w.spread << '|'
    << w.scaleKm << '|' << w.seed << '|' << w.resolution << '|' << enumName(w.cloudType) << '|'
    << enumName(w.cover);
  for (const WeatherLevelSettings* l : {&w.low, &w.mid, &w.high})
    s << '|' << l->bottomHpa << ',' << l->topHpa << ',' << l->rhCritical;
  s << '|' << enumName(w.advection) << '|' << w.steeringHpa << '|' << enumName(w.evolution);
  if (w.advection == WeatherAdvection::Wind)
    s << '|' << in.windMs.x << ',' << in.windMs.y;
  if (w.evolution == WeatherEvolution::Ca)
    s << '|' << w.automaton.stepS << ',' << w.automaton.windowH << ',' << w.automaton.lifetimeMin
      << ',' << w.automaton.strength;
  if (w.source == WeatherMapSource::Image) s << '|' << fileStamp(in.image);
  return s.str();
}

double unixTime(const IsoTime& t) {
  return double(t.unixSeconds) + t.subsecond;
}

}  // namespace

double weatherTimeUnix(const WeatherInputs& in, const IsoTime& frame) {
  if (!in.settings.time) return unixTime(frame);
  return unixTime(*in.settings.time) + frame.secondsSince(in.start);
}

WeatherMap WeatherSource::moved(const WeatherInputs& in, double timeUnix) {
  const WeatherSettings& w = in.settings;
  if (w.source == WeatherMapSource::File)
    return weatherMapFromFields(*mFields, timeUnix, w, mRegion, in.windMs);
  WeatherMap map = *mStill;
  // A painted or procedural map shows the scene's first frame; the wind carries it from there.
  const double seconds = timeUnix - weatherTimeUnix(in, in.start);
  if (w.advection == WeatherAdvection::Wind && seconds != 0.0) advectMap(map, in.windMs, seconds);
  return map;
}

void WeatherSource::evolve(const WeatherInputs& in, const std::string& signature,
                           double timeUnix, WeatherMap& map) {
  // Between two forecast steps the automaton runs from one to the next, so the data hold
  // exactly at the steps; elsewhere (a single step, a painted or procedural map) in fixed
  // windows of automaton.window_h.
  std::pair<double, double> window = automatonWindow(timeUnix, in.settings.automaton);
  if (mFields && in.settings.source == WeatherMapSource::File) {
    const std::vector<WeatherStep>& steps = mFields->steps;
    for (size_t i = 0; i + 1 < steps.size(); ++i)
      if (timeUnix >= steps[i].validTimeUnix && timeUnix < steps[i + 1].validTimeUnix)
        window = {steps[i].validTimeUnix, steps[i + 1].validTimeUnix};
  }
  std::ostringstream key;
  key.precision(17);
  key << signature << "|w" << window.first << ',' << window.second;
  if (!mEnds[0] || !mEnds[1] || key.str() != mEndsSignature) {
    mEnds[0].reset();
    mEnds[1].reset();
    mEnds[0] = moved(in, window.first);
    mEnds[1] = moved(in, window.second);
    mEndsSignature = key.str();
  }
  mAutomaton.apply(map, *mEnds[0], *mEnds[1], window.first, window.second, timeUnix, in.settings);
}

const WeatherMap& WeatherSource::map(const WeatherInputs& in, const IsoTime& frame) {
  const WeatherSettings& w = in.settings;
  if (w.advection == WeatherAdvection::Data && w.source != WeatherMapSource::File)
    inputError(
        "weather.advection: data needs source file (the wind comes from the forecast); "
        "use wind for the scene's wind");
  std::string signature;
  if (w.source == WeatherMapSource::File) {
    const std::string stamp = filesStamp(in);
    if (!mFields || stamp != mFieldsStamp) {
      mFields.reset();  // a failed read leaves nothing stale behind
      mMap.reset();
      mFields = readWeatherFile(in);
      mDataRegion = dataRegion(mFields->grid);  // a pass over every grid point: once per file
      mFieldsStamp = stamp;
    }
    mRegion = w.region || !mWholeData ? mapRegion(in, &mDataRegion) : mDataRegion;
    signature = settingsSignature(in, mRegion) + '|' + stamp;
  } else {
    mRegion = mapRegion(in);
    signature = settingsSignature(in, mRegion);
    if (!mStill || signature != mStillSignature) {
      mStill.reset();
      mMap.reset();
      mStill = makeWeatherMap(in, mRegion);
      mStillSignature = signature;
    }
  }
  const double t = weatherTimeUnix(in, frame);
  // Whether the map changes with time: between a file's steps the cover is interpolated,
  // advection carries it, the automaton evolves it.
  const bool timeDependent = (w.source == WeatherMapSource::File && mFields->steps.size() > 1) ||
                             w.advection != WeatherAdvection::None ||
                             w.evolution == WeatherEvolution::Ca;
  const std::string base = signature;
  if (timeDependent) {
    std::ostringstream s;
    s.precision(17);
    s << "|t" << t;
    signature += s.str();
  }
  if (!mMap || signature != mMapSignature) {
    mMap.reset();
    mMapSignature = signature;
    WeatherMap map = moved(in, t);
    if (w.evolution == WeatherEvolution::Ca) evolve(in, base, t, map);
    mMap = std::move(map);
    ++mRevision;
  }
  return *mMap;
}

}  // namespace sky
