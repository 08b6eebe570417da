#include "engine/weather/cloud_automaton.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "engine/core/error.h"

namespace sky {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr uint32_t kCertain = CloudVoxelGrid::kCertain;

// ---- Random numbers -------------------------------------------------------------------------
// Counter-based: every row of voxels draws from its own SplitMix64 stream whose start is a hash
// of (seed, window start, layer, step, row), so no result depends on the order or number of
// earlier calls, frames or threads.

constexpr uint64_t kGolden = 0x9e3779b97f4a7c15ull;

uint64_t mix64(uint64_t z) {  // SplitMix64's finaliser
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

uint64_t hashCombine(uint64_t h, uint64_t v) {
  return mix64(h ^ mix64(v + kGolden));
}

struct Stream {
  uint64_t state;
  uint64_t next() { return mix64(state += kGolden); }
};

// Lanes of `eligible` each set with the same probability t / 2^32 (kCertain: all): a bit-sliced
// comparison of 64 uniform numbers, drawn one bit at a time from the most significant, against
// t; a lane is decided at the first bit where its number and t differ, and the loop ends when
// all are (after about 8 draws).
uint64_t drawUniform(uint64_t eligible, uint32_t t, Stream& rng) {
  if (eligible == 0 || t == 0) return 0;
  if (t == kCertain) return eligible;
  uint64_t below = 0, open = eligible;
  for (int b = 31; b >= 0 && open != 0; --b) {
    const uint64_t r = rng.next();
    const uint64_t tb = ((t >> b) & 1u) ? ~uint64_t(0) : 0;
    below |= open & tb & ~r;  // the number has 0 where t has 1: it is below t
    open &= ~(tb ^ r);        // still equal so far
  }
  return below;  // lanes equal to t in all 32 bits are not below it
}

// Per-lane probabilities are compared eight lanes to a word (SWAR): a random byte per lane
// against the first byte of its threshold, the remaining 24 bits only where those tie (one
// lane in 256). The cost does not depend on the probabilities.
constexpr uint64_t kHighBits = 0x8080808080808080ull;
constexpr uint64_t kLowBits = 0x0101010101010101ull;
static_assert(std::endian::native == std::endian::little, "lane j of a group is its byte j");

// The high bit of each byte where a's byte is below b's (unsigned).
uint64_t bytesBelow(uint64_t a, uint64_t b) {
  const uint64_t lowNotBelow = (a | kHighBits) - (b & ~kHighBits);  // no borrow between bytes
  return ((~a & b) | (~(a ^ b) & ~lowNotBelow)) & kHighBits;
}

// The high bit of each byte where a's and b's bytes are equal.
uint64_t bytesEqual(uint64_t a, uint64_t b) {
  const uint64_t x = a ^ b;
  return ~(((x & ~kHighBits) + ~kHighBits) | x) & kHighBits;
}

// Whether any byte of a equals b's: never misses one (may see one that is not there).
bool mayHaveEqualByte(uint64_t a, uint64_t b) {
  const uint64_t x = a ^ b;
  return ((x - kLowBits) & ~x & kHighBits) != 0;
}

// Byte j's high bit to bit j.
uint64_t gatherHighBits(uint64_t m) {
  return ((m >> 7) * 0x0102040810204080ull) >> 56;
}

// The thresholds of one word (64 columns of a row).
struct LaneThresholds {
  const uint32_t* value = nullptr;
  std::array<uint32_t, 64> padded{};  // the last word's, zero beyond the width
  std::array<uint8_t, 64> first{};    // value >> 24, the byte compared first
  uint64_t some = 0;                  // the groups of eight lanes with any p > 0, all their bits
};

void laneThresholds(const uint32_t* t, uint32_t lanes, LaneThresholds& out) {
  if (lanes < 64) {
    std::copy(t, t + lanes, out.padded.begin());
    std::fill(out.padded.begin() + lanes, out.padded.end(), 0u);
    t = out.padded.data();
  }
  out.value = t;
  for (uint32_t i = 0; i < 64; ++i) out.first[i] = uint8_t(t[i] >> 24);
  uint64_t some = 0;
  for (uint32_t g = 0; g < 8; ++g) {
    const uint32_t* v = t + 8 * g;
    if ((v[0] | v[1] | v[2] | v[3] | v[4] | v[5] | v[6] | v[7]) != 0)
      some |= uint64_t(0xff) << (8 * g);
  }
  out.some = some;
}

// One uniform number per lane, compared with two thresholds: lanes of `eligibleA` below a's,
// and lanes of `eligibleB` below b's (exactly threshold / 2^32 each, or 1 for kCertain). A group
// of eight lanes with nothing to draw takes no random numbers. Drawing a against an empty
// `eligibleB` (or the reverse) gives independent draws.
std::pair<uint64_t, uint64_t> drawLanes(uint64_t eligibleA, const LaneThresholds& a,
                                        uint64_t eligibleB, const LaneThresholds& b, Stream& rng) {
  const uint64_t openA = eligibleA & a.some, openB = eligibleB & b.some;
  const uint64_t open = openA | openB;
  if (open == 0) return {0, 0};
  uint64_t belowA = 0, belowB = 0, tiesA = 0, tiesB = 0;
  for (uint32_t g = 0; g < 8; ++g) {
    const uint32_t shift = 8 * g;
    if (((open >> shift) & 0xffu) == 0) continue;
    uint64_t firstA, firstB;
    std::memcpy(&firstA, a.first.data() + shift, 8);
    std::memcpy(&firstB, b.first.data() + shift, 8);
    const uint64_t r = rng.next();
    belowA |= gatherHighBits(bytesBelow(r, firstA)) << shift;
    belowB |= gatherHighBits(bytesBelow(r, firstB)) << shift;
    if (mayHaveEqualByte(r, firstA)) tiesA |= gatherHighBits(bytesEqual(r, firstA)) << shift;
    if (mayHaveEqualByte(r, firstB)) tiesB |= gatherHighBits(bytesEqual(r, firstB)) << shift;
  }
  // Lanes whose first byte ties: the same 24 further bits of the lane's number for both.
  tiesA &= openA;
  tiesB &= openB;
  for (uint64_t tie = tiesA | tiesB; tie != 0; tie &= tie - 1) {
    const int i = std::countr_zero(tie);
    const uint64_t bit = uint64_t(1) << i;
    const uint32_t rest = uint32_t(rng.next()) & 0xffffffu;
    const uint32_t va = a.value[size_t(i)], vb = b.value[size_t(i)];
    if ((tiesA & bit) && (va == kCertain || rest < (va & 0xffffffu))) belowA |= bit;
    if ((tiesB & bit) && (vb == kCertain || rest < (vb & 0xffffffu))) belowB |= bit;
  }
  return {belowA & openA, belowB & openB};
}

// ---- Calibration ----------------------------------------------------------------------------
// The supply follows one parameter u in [0, 1]. Up to the knee u_s = 1 / (1 + p_ext), with
// a = u / (1 - u):  p_hum = a p_ext, p_act = kActivationRatio a p_ext.
// In mean field a cloud voxel forms at about p_hum (1 - cloud) per step and dissolves at
// p_ext cloud, so the cloud fraction is near a / (1 + a) = u. At the knee p_hum reaches 1;
// beyond it p_act rises linearly to 1 at u = 1, where every voxel is activated every step (a
// full layer). Fires spreading through the humid voxels (f_act) and the discreteness of the
// steps move the cloud fraction from u by up to about 0.06, hence a table measured by
// simulation. kActivationRatio sets how far humidity accumulates before it is activated: small
// values let it approach the percolation threshold of the f_act neighbourhood, where single
// activations burn large fractal clusters and the mean cloud fraction jumps in bursts; at 0.1
// clusters stay a few voxels across and the mean is steady.
constexpr double kActivationRatio = 0.1;
// Below this extinction the table is calibrated at it and its probabilities scaled by
// p_ext / kReferenceExtinction (all but cover 1's): with every probability proportional to
// p_ext the steady state depends on the ratios alone in the limit of small probabilities
// (measured: at p_ext 0.008 the steady state lies within 0.025 of the cover, against 0.005 at
// p_ext 0.05 to 1 calibrated directly), and simulating at the real, smaller p_ext would take
// steps in proportion to 1 / p_ext.
constexpr double kReferenceExtinction = 0.05;
// Simulated u: kKneeNodes up to the knee, kTopNodes - 1 between it and 1.
constexpr int kKneeNodes = 20, kTopNodes = 6;
constexpr int kCoverNodes = 1024;  // the table's covers: c = j / kCoverNodes
// The calibration grid (open edges like the map's; measured away from them) and its run,
// in units of the relaxation time 1 / p_ext, and at least so many steps (humidity relaxes
// over its own time, which matters where cloud dissolves within a few steps). Two runs with
// other random numbers agree within 0.006 at every node.
constexpr uint32_t kCalibrationWidth = 64, kCalibrationHeight = 24, kCalibrationMargin = 4;
constexpr double kCalibrationBurnIn = 2.0, kCalibrationMeasure = 8.0;
constexpr int kCalibrationMinBurnIn = 20, kCalibrationMinMeasure = 40;
constexpr uint64_t kCalibrationKey = 0x63616c6962726174ull;  // "calibrat"

double knee(double pExt) {
  return 1.0 / (1.0 + pExt);
}

// The probabilities of parameter u at extinction pExt.
std::pair<double, double> supplyOf(double u, double pExt) {
  if (u <= 0.0) return {0.0, 0.0};
  if (u >= 1.0) return {1.0, 1.0};
  const double us = knee(pExt);
  if (u >= us) return {1.0, kActivationRatio + (1.0 - kActivationRatio) * (u - us) / (1.0 - us)};
  const double a = u / (1.0 - u);
  return {std::min(1.0, a * pExt), std::min(1.0, kActivationRatio * a * pExt)};
}

// A simulated u: its steady-state cloud and hum fractions.
struct Node {
  double u, cloud, hum;
};

std::vector<Node> simulateNodes(double pExt) {
  const uint32_t w = kCalibrationWidth, h = kCalibrationHeight, m = kCalibrationMargin;
  const size_t columns = size_t(w) * h;
  const int burnIn = std::max(kCalibrationMinBurnIn, int(std::ceil(kCalibrationBurnIn / pExt)));
  const int measure = std::max(kCalibrationMinMeasure, int(std::ceil(kCalibrationMeasure / pExt)));
  const double us = knee(pExt);
  std::vector<Node> nodes{{0.0, 0.0, 0.0}};
  double humSeed = 0.1;  // the previous node's, so each run starts near its steady state
  for (int i = 1; i < kKneeNodes + kTopNodes; ++i) {
    const double u =
        i <= kKneeNodes ? us * i / kKneeNodes : us + (1.0 - us) * (i - kKneeNodes) / kTopNodes;
    const auto [pHum, pAct] = supplyOf(u, pExt);
    const std::vector<uint32_t> cld(columns, CloudVoxelGrid::threshold(u));
    const std::vector<uint32_t> hum(columns, CloudVoxelGrid::threshold(humSeed));
    const std::vector<uint32_t> tHum(columns, CloudVoxelGrid::threshold(pHum));
    const std::vector<uint32_t> tAct(columns, CloudVoxelGrid::threshold(pAct));
    CloudVoxelGrid grid(w, h);
    const uint64_t key = hashCombine(kCalibrationKey, uint64_t(i));
    grid.seed(cld, hum, key);
    double cloudSum = 0.0, humSum = 0.0;
    for (int s = 0; s < burnIn + measure; ++s) {
      grid.step(pExt, tHum, tAct, hashCombine(key, uint64_t(s)));
      if (s < burnIn) continue;
      cloudSum += grid.cloudFraction(m, m, w - m, h - m);
      humSum += grid.humFraction(m, m, w - m, h - m);
    }
    nodes.push_back({u, cloudSum / measure, humSum / measure});
    humSeed = nodes.back().hum;
  }
  nodes.push_back({1.0, 1.0, 0.0});  // every voxel activated each step: all cloud, no hum left
  // The true curve rises with u; keep the measured one strictly rising so it inverts.
  for (size_t i = 1; i < nodes.size(); ++i)
    nodes[i].cloud = std::max(nodes[i].cloud, nodes[i - 1].cloud + 1e-6);
  nodes.back().cloud = 1.0;
  return nodes;
}

// Thresholds (and probabilities) at the covers j / kCoverNodes.
struct SupplyTable {
  std::array<uint32_t, kCoverNodes + 1> hum{}, act{}, seedHum{};
  std::array<double, kCoverNodes + 1> pHum{}, pAct{}, humFraction{};
};

// The table for pExt from nodes simulated at `simulated` (pExt or the reference): the nodes
// inverted (u linear between them), the probabilities of each u at `simulated`, scaled to pExt.
std::unique_ptr<SupplyTable> buildTable(const std::vector<Node>& nodes, double simulated,
                                        double pExt) {
  auto t = std::make_unique<SupplyTable>();
  const double scale = pExt / simulated;
  size_t k = 0;
  for (size_t j = 0; j <= size_t(kCoverNodes); ++j) {
    const double c = double(j) / kCoverNodes;
    while (k + 2 < nodes.size() && nodes[k + 1].cloud < c) ++k;
    const Node& a = nodes[k];
    const Node& b = nodes[k + 1];
    const double f = std::clamp((c - a.cloud) / (b.cloud - a.cloud), 0.0, 1.0);
    const double u = j == 0 ? 0.0 : j == size_t(kCoverNodes) ? 1.0 : std::lerp(a.u, b.u, f);
    const auto [pHum, pAct] = supplyOf(u, simulated);
    t->pHum[j] = u >= 1.0 ? 1.0 : pHum * scale;
    t->pAct[j] = u >= 1.0 ? 1.0 : pAct * scale;
    t->humFraction[j] = j == 0 ? 0.0 : std::lerp(a.hum, b.hum, f);
    t->hum[j] = CloudVoxelGrid::threshold(t->pHum[j]);
    t->act[j] = CloudVoxelGrid::threshold(t->pAct[j]);
    t->seedHum[j] = CloudVoxelGrid::threshold(t->humFraction[j]);
  }
  return t;
}

// Calibrated once per process and extinction (the simulation once per simulated extinction);
// references stay valid for the process's life.
const SupplyTable& supplyTable(double pExt) {
  static std::mutex mutex;
  static std::map<double, std::vector<Node>> calibrations;
  static std::map<double, std::unique_ptr<SupplyTable>> tables;
  const std::lock_guard lock(mutex);
  auto found = tables.find(pExt);
  if (found != tables.end()) return *found->second;
  const double simulated = std::max(pExt, kReferenceExtinction);
  auto cal = calibrations.find(simulated);
  if (cal == calibrations.end())
    cal = calibrations.emplace(simulated, simulateNodes(simulated)).first;
  return *tables.emplace(pExt, buildTable(cal->second, simulated, pExt)).first->second;
}

// Cover clamped to [0, 1], NaN to 0.
float clampCover(float c) {
  return c > 0.0f ? std::min(c, 1.0f) : 0.0f;
}

// The table node nearest to a cover in [0, 1] (up to rounding).
size_t coverNode(float c) {
  return std::min(size_t(c * float(kCoverNodes) + 0.5f), size_t(kCoverNodes));
}

}  // namespace

double automatonExtinction(const WeatherAutomatonSettings& settings) {
  return 1.0 - std::exp(-settings.stepS / (60.0 * settings.lifetimeMin));
}

std::pair<double, double> automatonWindow(double timeUnix,
                                          const WeatherAutomatonSettings& settings) {
  const double length = settings.windowH * 3600.0;
  const double start = std::floor(timeUnix / length) * length;
  return {start, start + length};
}

AutomatonSupply automatonSupply(double cover, double pExt) {
  const SupplyTable& t = supplyTable(pExt);
  const size_t j = coverNode(clampCover(float(cover)));
  return {t.pHum[j], t.pAct[j], t.humFraction[j]};
}

// ---- CloudVoxelGrid -------------------------------------------------------------------------

uint32_t CloudVoxelGrid::threshold(double p) {
  if (!(p > 0.0)) return 0;  // NaN too
  if (p >= 1.0) return kCertain;
  return uint32_t(std::min(p * 4294967296.0, double(kCertain - 1)));
}

CloudVoxelGrid::CloudVoxelGrid(uint32_t width, uint32_t height, uint32_t depth)
    : mWidth(width), mHeight(height), mDepth(depth), mWordsPerRow((width + 63) / 64) {
  // columnCloudFraction counts a column's levels in a byte.
  if (depth == 0 || depth > 255)
    internalError("CloudVoxelGrid: " + std::to_string(depth) + " levels, 1 to 255 expected");
  const size_t words = size_t(mWordsPerRow) * height * depth;
  mHum.assign(words, 0);
  mAct.assign(words, 0);
  mCld.assign(words, 0);
}

bool CloudVoxelGrid::operator==(const CloudVoxelGrid& o) const {
  return mWidth == o.mWidth && mHeight == o.mHeight && mDepth == o.mDepth && mHum == o.mHum &&
         mAct == o.mAct && mCld == o.mCld;
}

uint64_t CloudVoxelGrid::validBits(uint32_t wordX) const {
  const uint32_t rest = mWidth - wordX * 64;
  return rest >= 64 ? ~uint64_t(0) : (uint64_t(1) << rest) - 1;
}

CloudVoxelGrid::Voxel CloudVoxelGrid::get(uint32_t x, uint32_t y, uint32_t z) const {
  const size_t i = wordIndex(x / 64, y, z);
  const uint32_t b = x % 64;
  return {bool((mHum[i] >> b) & 1u), bool((mAct[i] >> b) & 1u), bool((mCld[i] >> b) & 1u)};
}

void CloudVoxelGrid::set(uint32_t x, uint32_t y, uint32_t z, Voxel v) {
  const size_t i = wordIndex(x / 64, y, z);
  const uint64_t bit = uint64_t(1) << (x % 64);
  mHum[i] = v.hum ? mHum[i] | bit : mHum[i] & ~bit;
  mAct[i] = v.act ? mAct[i] | bit : mAct[i] & ~bit;
  mCld[i] = v.cld ? mCld[i] | bit : mCld[i] & ~bit;
}

namespace {
void checkColumns(const char* what, size_t a, size_t b, size_t columns) {
  if (a != columns || b != columns)
    internalError(std::string("CloudVoxelGrid::") + what + ": thresholds for " + std::to_string(a) +
                  " and " + std::to_string(b) + " columns, the grid has " +
                  std::to_string(columns));
}
}  // namespace

namespace {
// The walk seed() and perturb() share: every word of the grid row by row, with one random
// stream per (y, z) row of voxels keyed by `key` (so a row's draws do not depend on any other
// row's), and the thresholds of the two per-column probability sets `a` and `b` for the word's
// 64 columns. Calls f(wordX, y, z, thresholdsA, thresholdsB, stream).
template <class F>
void forEachWord(uint32_t width, uint32_t height, uint32_t depth, std::span<const uint32_t> a,
                 std::span<const uint32_t> b, uint64_t key, F&& f) {
  LaneThresholds ta, tb;
  std::vector<Stream> rows(depth);
  const uint32_t wordsPerRow = (width + 63) / 64;
  for (uint32_t y = 0; y < height; ++y) {
    for (uint32_t z = 0; z < depth; ++z) rows[z] = {hashCombine(key, uint64_t(z) * height + y)};
    for (uint32_t wx = 0; wx < wordsPerRow; ++wx) {
      const size_t column = size_t(y) * width + size_t(wx) * 64;
      const uint32_t lanes = std::min(64u, width - wx * 64);
      laneThresholds(a.data() + column, lanes, ta);
      laneThresholds(b.data() + column, lanes, tb);
      for (uint32_t z = 0; z < depth; ++z) f(wx, y, z, ta, tb, rows[z]);
    }
  }
}
}  // namespace

void CloudVoxelGrid::seed(std::span<const uint32_t> cld, std::span<const uint32_t> hum,
                          uint64_t key) {
  checkColumns("seed", cld.size(), hum.size(), size_t(mWidth) * mHeight);
  forEachWord(mWidth, mHeight, mDepth, cld, hum, key,
              [&](uint32_t wx, uint32_t y, uint32_t z, const LaneThresholds& tCld,
                  const LaneThresholds& tHum, Stream& rng) {
                const size_t i = wordIndex(wx, y, z);
                const uint64_t valid = validBits(wx);
                mCld[i] = drawLanes(valid, tCld, 0, tHum, rng).first;
                mHum[i] = drawLanes(0, tCld, valid, tHum, rng).second;
                mAct[i] = 0;
              });
}

void CloudVoxelGrid::perturb(double pExt, std::span<const uint32_t> hum,
                             std::span<const uint32_t> act, uint64_t key) {
  checkColumns("perturb", hum.size(), act.size(), size_t(mWidth) * mHeight);
  const uint32_t tExt = threshold(pExt);
  forEachWord(mWidth, mHeight, mDepth, hum, act, key,
              [&](uint32_t wx, uint32_t y, uint32_t z, const LaneThresholds& tHum,
                  const LaneThresholds& tAct, Stream& rng) {
                const size_t i = wordIndex(wx, y, z);
                const uint64_t valid = validBits(wx);
                // Dobashi: cld &= rnd > p_ext; hum |= rnd < p_hum; act |= rnd < p_act.
                mCld[i] &= ~drawUniform(mCld[i], tExt, rng);
                const auto [h, a] = drawLanes(valid & ~mHum[i], tHum, valid & ~mAct[i], tAct, rng);
                mHum[i] |= h;
                mAct[i] |= a;
              });
}

void CloudVoxelGrid::grow() {
  std::vector<uint64_t>& next = mActNext;
  next.resize(mAct.size());  // every word is written below
  const std::vector<uint64_t> zeros(mWordsPerRow, 0);
  // The act row at (y, z), or zeros outside the grid.
  auto row = [&](int64_t y, int64_t z) -> const uint64_t* {
    if (y < 0 || y >= int64_t(mHeight) || z < 0 || z >= int64_t(mDepth)) return zeros.data();
    return mAct.data() + wordIndex(0, uint32_t(y), uint32_t(z));
  };
  for (int64_t z = 0; z < int64_t(mDepth); ++z) {
    for (int64_t y = 0; y < int64_t(mHeight); ++y) {
      const uint64_t* a = row(y, z);
      const uint64_t *yM1 = row(y - 1, z), *yP1 = row(y + 1, z), *yM2 = row(y - 2, z),
                     *yP2 = row(y + 2, z), *zM1 = row(y, z - 1), *zP1 = row(y, z + 1),
                     *zM2 = row(y, z - 2);
      const size_t base = wordIndex(0, uint32_t(y), uint32_t(z));
      for (uint32_t wx = 0; wx < mWordsPerRow; ++wx) {
        const uint64_t act = a[wx];
        const uint64_t prev = wx > 0 ? a[wx - 1] : 0;  // x - 64 .. x - 1
        const uint64_t nxt = wx + 1 < mWordsPerRow ? a[wx + 1] : 0;
        // Dobashi's f_act: bit x holds act at x - 1, x - 2 (shift up), x + 1, x + 2 (down).
        uint64_t f = (act << 1) | (prev >> 63) | (act << 2) | (prev >> 62) | (act >> 1) |
                     (nxt << 63) | (act >> 2) | (nxt << 62);
        f |= yM1[wx] | yP1[wx] | yM2[wx] | yP2[wx] | zM1[wx] | zP1[wx] | zM2[wx];
        const size_t i = base + wx;
        const uint64_t hum = mHum[i];  // 0 beyond the width, so act' is too
        next[i] = ~act & hum & f;      // act' = !act & hum & f_act
        mHum[i] = hum & ~act;          // hum' = hum & !act
        mCld[i] |= act;                // cld' = cld | act
      }
    }
  }
  mAct.swap(next);
}

void CloudVoxelGrid::step(double pExt, std::span<const uint32_t> hum, std::span<const uint32_t> act,
                          uint64_t key) {
  perturb(pExt, hum, act, key);
  grow();
}

namespace {
// Byte j of kSpreadBits[b] is bit j of b: adds eight lanes' bits to eight byte counters at once.
constexpr std::array<uint64_t, 256> kSpreadBits = [] {
  std::array<uint64_t, 256> t{};
  for (uint64_t b = 0; b < 256; ++b)
    for (uint64_t j = 0; j < 8; ++j) t[b] |= ((b >> j) & 1u) << (8 * j);
  return t;
}();
}  // namespace

void CloudVoxelGrid::columnCloudFraction(std::span<float> out) const {
  if (out.size() != size_t(mWidth) * mHeight)
    internalError("CloudVoxelGrid::columnCloudFraction: output of " + std::to_string(out.size()) +
                  " columns, the grid has " + std::to_string(size_t(mWidth) * mHeight));
  std::array<uint64_t, 8> count{};  // byte j of count[g]: lane 8 g + j (depth < 256)
  std::array<uint8_t, 64> lane{};
  const float scale = 1.0f / float(mDepth);
  for (uint32_t y = 0; y < mHeight; ++y) {
    for (uint32_t wx = 0; wx < mWordsPerRow; ++wx) {
      count.fill(0);
      for (uint32_t z = 0; z < mDepth; ++z) {
        const uint64_t c = mCld[wordIndex(wx, y, z)];
        for (uint32_t g = 0; g < 8; ++g) count[g] += kSpreadBits[(c >> (8 * g)) & 0xffu];
      }
      std::memcpy(lane.data(), count.data(), 64);
      const uint32_t lanes = std::min(64u, mWidth - wx * 64);
      float* o = out.data() + size_t(y) * mWidth + size_t(wx) * 64;
      for (uint32_t b = 0; b < lanes; ++b) o[b] = float(lane[b]) * scale;
    }
  }
}

double CloudVoxelGrid::fraction(const std::vector<uint64_t>& bits, uint32_t x0, uint32_t y0,
                                uint32_t x1, uint32_t y1) const {
  x1 = std::min(x1, mWidth);
  y1 = std::min(y1, mHeight);
  if (x0 >= x1 || y0 >= y1) return 0.0;
  uint64_t set = 0;
  for (uint32_t z = 0; z < mDepth; ++z)
    for (uint32_t y = y0; y < y1; ++y)
      for (uint32_t wx = x0 / 64; wx <= (x1 - 1) / 64; ++wx) {
        uint64_t mask = ~uint64_t(0);
        if (wx == x0 / 64) mask &= ~uint64_t(0) << (x0 % 64);
        if (wx == (x1 - 1) / 64 && x1 % 64 != 0) mask &= (uint64_t(1) << (x1 % 64)) - 1;
        set += uint64_t(std::popcount(bits[wordIndex(wx, y, z)] & mask));
      }
  return double(set) / (double(x1 - x0) * (y1 - y0) * mDepth);
}

double CloudVoxelGrid::cloudFraction(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1) const {
  return fraction(mCld, x0, y0, x1, y1);
}

double CloudVoxelGrid::humFraction(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1) const {
  return fraction(mHum, x0, y0, x1, y1);
}

// ---- CloudAutomaton -------------------------------------------------------------------------

namespace {

// The cover channel of layer `l` (0 low R, 1 mid G, 2 high coverHigh) at texel i.
float coverOf(const WeatherMap& map, size_t l, size_t i) {
  return l == 0 ? map.texels[i].r : l == 1 ? map.texels[i].g : map.coverHigh[i];
}

std::vector<float> coverChannel(const WeatherMap& map, size_t l) {
  std::vector<float> out(map.texels.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = clampCover(coverOf(map, l, i));
  return out;
}

uint64_t layerKey(int seed, double t0, size_t layer) {
  uint64_t h = hashCombine(0x736b796c61796572ull, uint64_t(uint32_t(seed)));  // "skylayer"
  h = hashCombine(h, std::bit_cast<uint64_t>(t0));
  return hashCombine(h, uint64_t(layer));
}

constexpr uint64_t kSeedStep = ~uint64_t(0);  // the key's step for seeding

uint64_t stepKey(uint64_t layer, uint64_t step) {
  return hashCombine(layer, step);
}

}  // namespace

bool CloudAutomaton::sameInputs(const WeatherMap& start, const WeatherMap& end, double t0,
                                double t1, const WeatherSettings& settings) const {
  if (!mValid || t0 != mT0 || t1 != mT1 || settings.seed != mSeed ||
      settings.automaton.stepS != mSettings.stepS ||
      settings.automaton.lifetimeMin != mSettings.lifetimeMin || start.width != mWidth ||
      start.height != mHeight)
    return false;
  const size_t layers = start.coverHigh.empty() ? 2 : 3;
  if (layers != mLayers.size()) return false;
  for (size_t l = 0; l < layers; ++l)
    for (size_t i = 0; i < start.texels.size(); ++i)
      if (clampCover(coverOf(start, l, i)) != mLayers[l].start[i] ||
          clampCover(coverOf(end, l, i)) != mLayers[l].end[i])
        return false;
  return true;
}

void CloudAutomaton::restart(const WeatherMap& start, const WeatherMap& end, double t0, double t1,
                             const WeatherSettings& settings) {
  mT0 = t0;
  mT1 = t1;
  mSeed = settings.seed;
  mSettings = settings.automaton;
  mWidth = start.width;
  mHeight = start.height;
  const size_t texels = start.texels.size();
  mLayers.assign(start.coverHigh.empty() ? 2 : 3, Layer{});
  const SupplyTable& table = supplyTable(automatonExtinction(mSettings));
  mHumThreshold.resize(texels);
  mActThreshold.resize(texels);
  for (size_t l = 0; l < mLayers.size(); ++l) {
    Layer& layer = mLayers[l];
    layer.start = coverChannel(start, l);
    layer.end = coverChannel(end, l);
    // Seeding (Liu 3.2's initial state): cld with the start map's cover, hum with the steady
    // state's humid fraction for it, no act.
    for (size_t i = 0; i < texels; ++i) {
      mActThreshold[i] = CloudVoxelGrid::threshold(layer.start[i]);  // cld here
      mHumThreshold[i] = table.seedHum[coverNode(layer.start[i])];
    }
    layer.grid = CloudVoxelGrid(mWidth, mHeight);
    layer.grid.seed(mActThreshold, mHumThreshold, stepKey(layerKey(mSeed, t0, l), kSeedStep));
  }
  mStateStep = 0;
  mDensityStep = -1;
  mValid = true;
  mStats.restarted = true;
}

void CloudAutomaton::runStep(Layer& layer, size_t layerIndex) {
  const double pExt = automatonExtinction(mSettings);
  const SupplyTable& table = supplyTable(pExt);
  // Target cover at the step's time: the window's maps blended linearly.
  const float f = float(std::clamp(double(mStateStep) * mSettings.stepS / (mT1 - mT0), 0.0, 1.0));
  const size_t texels = layer.start.size();
  for (size_t i = 0; i < texels; ++i) {
    const float a = layer.start[i];
    const size_t j = coverNode(a + f * (layer.end[i] - a));
    mHumThreshold[i] = table.hum[j];
    mActThreshold[i] = table.act[j];
  }
  layer.grid.step(pExt, mHumThreshold, mActThreshold,
                  stepKey(layerKey(mSeed, mT0, layerIndex), uint64_t(mStateStep)));
}

void CloudAutomaton::smoothedDensity(const Layer& layer, std::vector<float>& out) {
  // Dobashi's smoothing of the binary cld field: the column mean, then a 5 x 5 binomial
  // filter (a Gaussian of sigma 1 texel) renormalised at the map's edges.
  constexpr std::array<float, 5> kWeights{1.0f, 4.0f, 6.0f, 4.0f, 1.0f};
  const size_t w = mWidth, h = mHeight;
  mColumn.resize(w * h);
  mBlur.resize(w * h);
  out.resize(w * h);
  layer.grid.columnCloudFraction(mColumn);
  // The filter at index i of n, with only the taps inside [0, n), renormalised.
  auto edge = [&](size_t i, size_t n, auto&& value) {
    float sum = 0.0f, weight = 0.0f;
    for (size_t k = 0; k < 5; ++k) {
      if (i + k < 2 || i + k - 2 >= n) continue;
      sum += kWeights[k] * value(i + k - 2);
      weight += kWeights[k];
    }
    return sum / weight;
  };
  for (size_t y = 0; y < h; ++y) {
    const float* c = mColumn.data() + y * w;
    float* b = mBlur.data() + y * w;
    for (size_t x = 0; x < w; ++x) {
      if (x >= 2 && x + 2 < w)
        b[x] = (c[x - 2] + 4.0f * c[x - 1] + 6.0f * c[x] + 4.0f * c[x + 1] + c[x + 2]) / 16.0f;
      else
        b[x] = edge(x, w, [&](size_t i) { return c[i]; });
    }
  }
  for (size_t y = 0; y < h; ++y) {
    float* o = out.data() + y * w;
    if (y >= 2 && y + 2 < h) {
      const float *r0 = mBlur.data() + (y - 2) * w, *r1 = r0 + w, *r2 = r1 + w, *r3 = r2 + w,
                  *r4 = r3 + w;
      for (size_t x = 0; x < w; ++x)
        o[x] = (r0[x] + 4.0f * r1[x] + 6.0f * r2[x] + 4.0f * r3[x] + r4[x]) / 16.0f;
    } else {
      for (size_t x = 0; x < w; ++x) o[x] = edge(y, h, [&](size_t i) { return mBlur[i * w + x]; });
    }
  }
}

void CloudAutomaton::advance(int64_t step) {
  auto runAll = [&] {
    for (size_t l = 0; l < mLayers.size(); ++l) runStep(mLayers[l], l);
    ++mStateStep;
    ++mStats.stepsRun;
  };
  if (mDensityStep == step) return;
  if (mDensityStep >= 0 && mDensityStep + 1 == step) {
    runAll();
    for (Layer& layer : mLayers) {
      layer.densityNow.swap(layer.densityNext);
      smoothedDensity(layer, layer.densityNext);
    }
    mDensityStep = step;
    return;
  }
  while (mStateStep < step) runAll();
  for (Layer& layer : mLayers) smoothedDensity(layer, layer.densityNow);
  runAll();
  for (Layer& layer : mLayers) smoothedDensity(layer, layer.densityNext);
  mDensityStep = step;
}

void CloudAutomaton::apply(WeatherMap& current, const WeatherMap& start, const WeatherMap& end,
                           double t0, double t1, double timeUnix, const WeatherSettings& settings) {
  mStats = {};
  const size_t texels = size_t(current.width) * current.height;
  auto sameShape = [&](const WeatherMap& m) {
    return m.width == current.width && m.height == current.height && m.texels.size() == texels &&
           m.coverHigh.empty() == current.coverHigh.empty() &&
           (m.coverHigh.empty() || m.coverHigh.size() == texels);
  };
  if (!sameShape(current) || !sameShape(start) || !sameShape(end))
    internalError(
        "CloudAutomaton::apply: the maps differ in size or in having a high layer (start " +
        std::to_string(start.width) + "x" + std::to_string(start.height) + ", end " +
        std::to_string(end.width) + "x" + std::to_string(end.height) + ", current " +
        std::to_string(current.width) + "x" + std::to_string(current.height) + ")");
  if (!(t1 > t0))
    internalError("CloudAutomaton::apply: empty window [" + std::to_string(t0) + ", " +
                  std::to_string(t1) + "]");
  const double s = (timeUnix - t0) / (t1 - t0);
  const double strength = std::clamp(settings.automaton.strength, 0.0, 1.0);
  // At the window's ends (and outside it) the map is the data's, exactly.
  if (!(s > 0.0 && s < 1.0) || strength == 0.0 || texels == 0) return;
  const double weight = strength * std::sin(kPi * s);

  const double stepS = settings.automaton.stepS;
  const int64_t step = int64_t(std::floor((timeUnix - t0) / stepS));
  if (!sameInputs(start, end, t0, t1, settings) || step < mDensityStep)
    restart(start, end, t0, t1, settings);
  advance(step);

  const float between = float(std::clamp((timeUnix - t0 - double(step) * stepS) / stepS, 0.0, 1.0));
  for (size_t l = 0; l < mLayers.size(); ++l) {
    const Layer& layer = mLayers[l];
    for (size_t i = 0; i < texels; ++i) {
      const float density = std::lerp(layer.densityNow[i], layer.densityNext[i], between);
      float& cover = l == 0   ? current.texels[i].r
                     : l == 1 ? current.texels[i].g
                              : current.coverHigh[i];
      cover = float(cover + weight * (density - cover));
    }
  }
}

}  // namespace sky
