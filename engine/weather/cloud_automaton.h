#pragma once
// Cloud growth and decay between forecast steps (weather.evolution "ca"): the cellular
// automaton of Liu, Liu, Wu 2015 section 3.2 (Nagel & Raschke 1992 with Dobashi et al. 2000's
// extinction and supply) on a voxel grid per cloud layer, seeded by the weather map at the
// start of a window and driven by the map's cover; its smoothed column cloud fraction
// modulates the map's cover between the window's ends, where the map is left exactly as the
// data give it. Deterministic: the state at a time is a pure function of the settings, the
// seed, the two maps and the time. See docs/weather.md.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "engine/scene/scene.h"
#include "engine/weather/weather_map.h"

namespace sky {

// Dobashi's extinction probability per step for the mean life of a cloud voxel:
// p_ext = 1 - exp(-stepS / (60 lifetimeMin)).
double automatonExtinction(const WeatherAutomatonSettings& settings);

// For maps without forecast steps: the window [t0, t1) of windowH hours that contains
// `timeUnix`, aligned to whole multiples of windowH since 1970-01-01T00:00Z.
std::pair<double, double> automatonWindow(double timeUnix,
                                          const WeatherAutomatonSettings& settings);

// Dobashi's supply probabilities per step for a column whose target cover is `cover` (clamped
// to 0..1; the nearest of 1025 tabulated covers), under extinction `pExt`: p_hum (humidity),
// p_act (activation) and the steady state's fraction of hum voxels (what seeding draws).
// Calibrated by simulation once per process and extinction (see cloud_automaton.cpp) so that
// the automaton's steady-state cloud fraction equals `cover`; cover 0 gives 0, 0 (no clouds
// ever form), cover 1 gives 1, 1 (every voxel cloudy after each step).
struct AutomatonSupply {
  double pHum = 0.0, pAct = 0.0, humFraction = 0.0;
};
AutomatonSupply automatonSupply(double cover, double pExt);

// One cloud layer's voxels: width x height map columns of `depth` levels (z up), each with the
// booleans hum, act and cld, packed 64 to a word along x. CloudAutomaton drives it; it is
// public so tests can check the rules on hand-made grids. Voxels outside the grid count as
// neither humid nor active.
class CloudVoxelGrid {
public:
  static constexpr uint32_t kDepth = 8;
  struct Voxel {
    bool hum = false, act = false, cld = false;
    bool operator==(const Voxel&) const = default;
  };

  CloudVoxelGrid() = default;
  CloudVoxelGrid(uint32_t width, uint32_t height, uint32_t depth = kDepth);

  uint32_t width() const { return mWidth; }
  uint32_t height() const { return mHeight; }
  uint32_t depth() const { return mDepth; }
  Voxel get(uint32_t x, uint32_t y, uint32_t z) const;
  void set(uint32_t x, uint32_t y, uint32_t z, Voxel v);
  bool operator==(const CloudVoxelGrid& other) const;  // same size and voxels

  // Probabilities as the grid takes them: p * 2^32 rounded down for p < 1 (at most
  // kCertain - 1), kCertain for p >= 1, 0 for p <= 0 or NaN; exact at both ends.
  static constexpr uint32_t kCertain = 0xffffffffu;
  static uint32_t threshold(double p);

  // Clears every voxel, then sets cld with probability cld[column] and hum with hum[column]
  // (thresholds, one per column: width x height, row-major like the map), independently, from
  // the random streams of `key`.
  void seed(std::span<const uint32_t> cld, std::span<const uint32_t> hum, uint64_t key);
  // Dobashi's stochastic transitions, each voxel on its own: cld cleared with probability
  // pExt; hum set where a uniform number rnd is below the column's hum threshold, act set where
  // the same rnd is below its act threshold (Dobashi's two rules with one rnd per voxel; where
  // act is set the growth rules clear hum anyway). Random numbers come from counter-based
  // streams of `key` (one per row of voxels), so the result depends on nothing but the state,
  // the thresholds and the key.
  void perturb(double pExt, std::span<const uint32_t> hum, std::span<const uint32_t> act,
               uint64_t key);
  // Nagel & Raschke's growth rules, all voxels at once: hum' = hum & !act, cld' = cld | act,
  // act' = !act & hum & f_act with Dobashi's f_act (act at x+-1, y+-1, z+-1, x+-2, y+-2, z-2).
  void grow();
  // One automaton step: perturb, then grow (so activation 1 leaves every voxel cloudy).
  void step(double pExt, std::span<const uint32_t> hum, std::span<const uint32_t> act,
            uint64_t key);
  // Per column (row-major), the fraction of its levels with cld set, 0..1.
  void columnCloudFraction(std::span<float> out) const;
  // The fraction of voxels with cld (or hum) set in the columns [x0, x1) x [y0, y1).
  double cloudFraction(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1) const;
  double humFraction(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1) const;

private:
  size_t wordIndex(uint32_t wordX, uint32_t y, uint32_t z) const {
    return (size_t(z) * mHeight + y) * mWordsPerRow + wordX;
  }
  uint64_t validBits(uint32_t wordX) const;
  double fraction(const std::vector<uint64_t>& bits, uint32_t x0, uint32_t y0, uint32_t x1,
                  uint32_t y1) const;

  uint32_t mWidth = 0, mHeight = 0, mDepth = 0, mWordsPerRow = 0;
  std::vector<uint64_t> mHum, mAct, mCld;  // bit x % 64 of word x / 64 of row (z, y)
  std::vector<uint64_t> mActNext;          // grow()'s scratch
};

// The automaton for a weather map: one CloudVoxelGrid per layer (low R, mid G, and high when
// the map has coverHigh), seeded at t0 with cld drawn at the start map's cover and hum at the
// steady state's humid fraction. Keeps its state between calls so frames at increasing times
// in one window continue from it; any call gives what a fresh object would, bit for bit.
// About 3 ms a step for a 256 x 256 map with three layers (one core), and once per process
// and extinction the calibration (automatonSupply, about 50 ms). Not thread-safe.
class CloudAutomaton {
public:
  // Replaces the cover channels (R, G, coverHigh; never B or A) of `current` (the map at
  // `timeUnix` as the caller built it) by mix(cover, density, strength * sin(pi s)) with
  // s = (timeUnix - t0) / (t1 - t0) and density the automaton's column cloud fraction
  // smoothed by a 5 x 5 binomial filter, at timeUnix (linear between the states after
  // floor((timeUnix - t0) / stepS) steps and one more, so it changes continuously). `start` and
  // `end` are the maps at the window's ends t0 < t1 (the forecast steps that bracket timeUnix, or
  // automatonWindow's); the automaton's target cover at step n is their linear blend at t0 + n
  // stepS. Outside (t0, t1), or with strength 0, `current` is left as it is. `settings.evolution`
  // is not looked at: callers call this for "ca" only. Internal error when the maps differ in size
  // or coverHigh presence, or t1 <= t0.
  void apply(WeatherMap& current, const WeatherMap& start, const WeatherMap& end, double t0,
             double t1, double timeUnix, const WeatherSettings& settings);

  struct Stats {
    int stepsRun = 0;        // automaton steps the last apply ran
    bool restarted = false;  // whether it reseeded from the window's start
  };
  const Stats& lastStats() const { return mStats; }

private:
  struct Layer {
    CloudVoxelGrid grid;
    std::vector<float> start, end;               // target cover at t0 and t1
    std::vector<float> densityNow, densityNext;  // smoothed density at steps mDensityStep, +1
  };
  bool sameInputs(const WeatherMap& start, const WeatherMap& end, double t0, double t1,
                  const WeatherSettings& settings) const;
  void restart(const WeatherMap& start, const WeatherMap& end, double t0, double t1,
               const WeatherSettings& settings);
  void advance(int64_t step);
  void runStep(Layer& layer, size_t layerIndex);
  void smoothedDensity(const Layer& layer, std::vector<float>& out);

  bool mValid = false;
  double mT0 = 0.0, mT1 = 0.0;
  int mSeed = 0;
  WeatherAutomatonSettings mSettings;
  uint32_t mWidth = 0, mHeight = 0;
  std::vector<Layer> mLayers;
  int64_t mStateStep = 0;     // the grids hold the state after this many steps
  int64_t mDensityStep = -1;  // densityNow is of this step, densityNext of the next (-1: none)
  std::vector<uint32_t> mHumThreshold, mActThreshold;  // scratch, one map each
  std::vector<float> mColumn, mBlur;
  Stats mStats;
};

}  // namespace sky
