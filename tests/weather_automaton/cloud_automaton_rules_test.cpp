// engine/weather/cloud_automaton.h's voxel grid on hand-made grids: Nagel & Raschke's growth
// rules with Dobashi's f_act neighbourhood (across the 64-voxel words, at the grid's edges),
// Dobashi's extinction and supply at probabilities 0 and 1, the probabilities themselves
// (statistically, uniform and per column), seeding, and the probability thresholds.
#include <cmath>
#include <cstdint>
#include <set>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "engine/weather/cloud_automaton.h"

namespace sky {
namespace {

using Voxel = CloudVoxelGrid::Voxel;
using Coord = std::tuple<uint32_t, uint32_t, uint32_t>;

std::vector<uint32_t> uniform(const CloudVoxelGrid& g, double p) {
  return std::vector<uint32_t>(size_t(g.width()) * g.height(), CloudVoxelGrid::threshold(p));
}

// Every voxel humid, none active or cloudy, except `active`.
CloudVoxelGrid humidGrid(uint32_t w, uint32_t h, const std::vector<Coord>& active) {
  CloudVoxelGrid g(w, h);
  for (uint32_t z = 0; z < g.depth(); ++z)
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) g.set(x, y, z, {true, false, false});
  for (const auto& [x, y, z] : active) g.set(x, y, z, {true, true, false});
  return g;
}

std::set<Coord> activeVoxels(const CloudVoxelGrid& g) {
  std::set<Coord> out;
  for (uint32_t z = 0; z < g.depth(); ++z)
    for (uint32_t y = 0; y < g.height(); ++y)
      for (uint32_t x = 0; x < g.width(); ++x)
        if (g.get(x, y, z).act) out.insert({x, y, z});
  return out;
}

// Dobashi's f_act seen from the active voxel: act' appears at x+-1, x+-2, y+-1, y+-2, z+-1
// and z+2 (a voxel is activated by act at z-2, so activation climbs two levels, sinks one).
std::set<Coord> dobashiNeighbours(uint32_t x, uint32_t y, uint32_t z) {
  return {{x - 1, y, z}, {x - 2, y, z}, {x + 1, y, z}, {x + 2, y, z}, {x, y - 1, z}, {x, y - 2, z},
          {x, y + 1, z}, {x, y + 2, z}, {x, y, z - 1}, {x, y, z + 1}, {x, y, z + 2}};
}

TEST(CloudVoxelGrid, ActivationSpreadsToDobashisNeighboursAcrossWords) {
  // x = 64 is bit 0 of the second word, x = 63 bit 63 of the first: the x neighbours cross.
  for (uint32_t x : {63u, 64u, 65u}) {
    CloudVoxelGrid g = humidGrid(130, 9, {{x, 4, 3}});
    g.grow();
    EXPECT_EQ(activeVoxels(g), dobashiNeighbours(x, 4, 3)) << "act at x = " << x;
    // The active voxel turned into cloud and used its humidity; nothing else became cloud.
    EXPECT_EQ(g.get(x, 4, 3), (Voxel{false, false, true}));
    EXPECT_EQ(g.get(x + 1, 4, 3), (Voxel{true, true, false}));
    EXPECT_EQ(g.get(x + 3, 4, 3), (Voxel{true, false, false}));
    EXPECT_EQ(g.get(x, 4, 1), (Voxel{true, false, false}));      // z - 2 is not a neighbour
    EXPECT_EQ(g.get(x + 1, 5, 3), (Voxel{true, false, false}));  // nor the diagonals
    EXPECT_DOUBLE_EQ(g.cloudFraction(0, 0, 130, 9), 1.0 / (130.0 * 9.0 * g.depth()));
  }
}

TEST(CloudVoxelGrid, ActivationNeedsHumidityAndLastsOneStep) {
  CloudVoxelGrid g(16, 16);
  g.set(8, 8, 4, {false, true, false});  // active, no humidity anywhere
  g.set(9, 8, 4, {true, false, true});   // a humid, cloudy neighbour
  g.grow();
  EXPECT_EQ(g.get(8, 8, 4), (Voxel{false, false, true}));  // cld' = cld | act, act' = 0
  EXPECT_EQ(g.get(9, 8, 4), (Voxel{true, true, true}));    // activated, still cloudy
  EXPECT_EQ(activeVoxels(g), (std::set<Coord>{{9, 8, 4}}));
  g.grow();  // the humid one burns out; nothing left to activate
  EXPECT_EQ(g.get(9, 8, 4), (Voxel{false, false, true}));
  EXPECT_TRUE(activeVoxels(g).empty());
}

TEST(CloudVoxelGrid, EdgesHaveNoNeighboursBeyondThem) {
  // Width 70: the last word holds 6 voxels; corners of the grid in x, y and z.
  CloudVoxelGrid g = humidGrid(70, 5, {{69, 0, 7}, {0, 4, 0}});
  g.grow();
  std::set<Coord> expected;
  for (const Coord& c : dobashiNeighbours(69, 0, 7))
    if (std::get<0>(c) < 70 && std::get<1>(c) < 5 && std::get<2>(c) < 8) expected.insert(c);
  for (const Coord& c : dobashiNeighbours(0, 4, 0))
    if (std::get<0>(c) < 70 && std::get<1>(c) < 5 && std::get<2>(c) < 8) expected.insert(c);
  EXPECT_EQ(activeVoxels(g), expected);
  EXPECT_EQ(expected.size(), 5u + 6u);  // x-1, x-2, y+1, y+2, z-1; x+1, x+2, y-1, y-2, z+1, z+2
}

TEST(CloudVoxelGrid, ExtinctionOneClearsEveryCloudZeroKeepsThem) {
  CloudVoxelGrid g(100, 7);
  const std::vector<uint32_t> none = uniform(g, 0.0), all = uniform(g, 1.0);
  g.seed(all, none, 11);
  EXPECT_DOUBLE_EQ(g.cloudFraction(0, 0, 100, 7), 1.0);
  g.perturb(0.0, none, none, 12);
  EXPECT_DOUBLE_EQ(g.cloudFraction(0, 0, 100, 7), 1.0);
  EXPECT_DOUBLE_EQ(g.humFraction(0, 0, 100, 7), 0.0);
  EXPECT_TRUE(activeVoxels(g).empty());
  g.perturb(1.0, none, none, 13);
  EXPECT_DOUBLE_EQ(g.cloudFraction(0, 0, 100, 7), 0.0);
}

TEST(CloudVoxelGrid, SupplyOneSetsEveryVoxelZeroNone) {
  CloudVoxelGrid g(100, 7);
  const std::vector<uint32_t> none = uniform(g, 0.0), all = uniform(g, 1.0);
  g.perturb(0.5, none, none, 1);
  EXPECT_DOUBLE_EQ(g.humFraction(0, 0, 100, 7), 0.0);
  EXPECT_TRUE(activeVoxels(g).empty());
  g.perturb(0.5, all, none, 2);
  EXPECT_DOUBLE_EQ(g.humFraction(0, 0, 100, 7), 1.0);
  EXPECT_TRUE(activeVoxels(g).empty());
  g.perturb(0.5, none, all, 3);
  EXPECT_EQ(activeVoxels(g).size(), 100u * 7u * g.depth());
  // One step with both at 1 (what cover 1 asks for): every voxel cloudy, none humid.
  g.step(0.5, all, all, 4);
  EXPECT_DOUBLE_EQ(g.cloudFraction(0, 0, 100, 7), 1.0);
  EXPECT_DOUBLE_EQ(g.humFraction(0, 0, 100, 7), 0.0);
}

// Binomial standard deviation of a fraction of n draws at probability p.
double sigma(double p, double n) {
  return std::sqrt(p * (1.0 - p) / n);
}

TEST(CloudVoxelGrid, DrawsFollowThePerColumnProbabilities) {
  // Left half p_hum 0.1, p_act 0.02; right half 0.7 and 0.4 (the SWAR comparison's groups mix
  // both near x = 128); extinction 0.25. Each fraction within 5 sigma (n = 128 x 64 x 8).
  const uint32_t w = 256, h = 64;
  CloudVoxelGrid g(w, h);
  std::vector<uint32_t> hum(size_t(w) * h), act(size_t(w) * h);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      hum[size_t(y) * w + x] = CloudVoxelGrid::threshold(x < 128 ? 0.1 : 0.7);
      act[size_t(y) * w + x] = CloudVoxelGrid::threshold(x < 128 ? 0.02 : 0.4);
    }
  const std::vector<uint32_t> none = uniform(g, 0.0), all = uniform(g, 1.0);
  g.seed(all, none, 5);
  g.perturb(0.25, hum, act, 6);
  const double n = 128.0 * h * g.depth();
  EXPECT_NEAR(g.humFraction(0, 0, 128, h), 0.1, 5 * sigma(0.1, n));
  EXPECT_NEAR(g.humFraction(128, 0, w, h), 0.7, 5 * sigma(0.7, n));
  EXPECT_NEAR(g.cloudFraction(0, 0, w, h), 0.75, 5 * sigma(0.75, 2 * n));
  size_t actLeft = 0, actRight = 0;
  for (const auto& [x, y, z] : activeVoxels(g)) {
    (x < 128 ? actLeft : actRight) += 1;
    // One rnd per voxel for both supply rules: where it falls below p_act it is below p_hum.
    EXPECT_TRUE(g.get(x, y, z).hum) << x << " " << y << " " << z;
  }
  EXPECT_NEAR(double(actLeft) / n, 0.02, 5 * sigma(0.02, n));
  EXPECT_NEAR(double(actRight) / n, 0.4, 5 * sigma(0.4, n));
}

TEST(CloudVoxelGrid, SmallProbabilitiesAreNotRoundedAway) {
  // p = 0.001 lies below the first byte the SWAR comparison looks at (1/256): the rest of the
  // threshold decides on ties. 2^20 voxels: expected 1049, 5 sigma = 162.
  const uint32_t w = 512, h = 256;
  CloudVoxelGrid g(w, h);
  g.perturb(0.0, uniform(g, 0.001), uniform(g, 0.0), 7);
  EXPECT_NEAR(g.humFraction(0, 0, w, h), 0.001, 5 * sigma(0.001, double(w) * h * g.depth()));
}

TEST(CloudVoxelGrid, SeedDrawsCloudAndHumidityIndependently) {
  const uint32_t w = 200, h = 50;
  CloudVoxelGrid g(w, h);
  g.seed(uniform(g, 0.3), uniform(g, 0.6), 9);
  const double n = double(w) * h * g.depth();
  EXPECT_NEAR(g.cloudFraction(0, 0, w, h), 0.3, 5 * sigma(0.3, n));
  EXPECT_NEAR(g.humFraction(0, 0, w, h), 0.6, 5 * sigma(0.6, n));
  EXPECT_TRUE(activeVoxels(g).empty());
  size_t both = 0;
  for (uint32_t z = 0; z < g.depth(); ++z)
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) both += g.get(x, y, z).hum && g.get(x, y, z).cld;
  EXPECT_NEAR(double(both) / n, 0.18, 5 * sigma(0.18, n));
}

TEST(CloudVoxelGrid, SameKeySameStateOtherKeyOtherState) {
  CloudVoxelGrid a(90, 30), b(90, 30), c(90, 30);
  for (CloudVoxelGrid* g : {&a, &b, &c}) g->seed(uniform(*g, 0.4), uniform(*g, 0.2), 21);
  EXPECT_EQ(a, b);
  EXPECT_EQ(a, c);
  for (uint64_t s = 0; s < 5; ++s) {
    a.step(0.15, uniform(a, 0.1), uniform(a, 0.01), 100 + s);
    b.step(0.15, uniform(b, 0.1), uniform(b, 0.01), 100 + s);
    c.step(0.15, uniform(c, 0.1), uniform(c, 0.01), 200 + s);
  }
  EXPECT_EQ(a, b);
  EXPECT_FALSE(a == c);
}

TEST(CloudVoxelGrid, ThresholdsAreExactAtTheEnds) {
  EXPECT_EQ(CloudVoxelGrid::threshold(0.0), 0u);
  EXPECT_EQ(CloudVoxelGrid::threshold(-1.0), 0u);
  EXPECT_EQ(CloudVoxelGrid::threshold(std::nan("")), 0u);
  EXPECT_EQ(CloudVoxelGrid::threshold(1.0), CloudVoxelGrid::kCertain);
  EXPECT_EQ(CloudVoxelGrid::threshold(2.0), CloudVoxelGrid::kCertain);
  EXPECT_EQ(CloudVoxelGrid::threshold(0.5), 0x80000000u);
  EXPECT_EQ(CloudVoxelGrid::threshold(1.0 - 1e-12), CloudVoxelGrid::kCertain - 1);
}

TEST(CloudVoxelGrid, ColumnCloudFractionCountsLevels) {
  CloudVoxelGrid g(70, 3);
  for (uint32_t z = 0; z < 3; ++z) g.set(66, 1, z, {false, false, true});
  for (uint32_t z = 0; z < g.depth(); ++z) g.set(5, 2, z, {false, false, true});
  std::vector<float> f(70 * 3);
  g.columnCloudFraction(f);
  for (size_t i = 0; i < f.size(); ++i) {
    const float expected = i == 70 + 66 ? 3.0f / 8.0f : i == 140 + 5 ? 1.0f : 0.0f;
    EXPECT_EQ(f[i], expected) << i;
  }
}

}  // namespace
}  // namespace sky
