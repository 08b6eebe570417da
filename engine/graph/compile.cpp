#include "engine/graph/compile.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <queue>
#include <set>
#include <utility>

#include "engine/core/error.h"

namespace sky {
namespace {

using Version = std::pair<uint32_t, uint32_t>;  // (resource, version)

bool reads(Access a) {
  return a != Access::StorageWriteCompute && a != Access::TransferDst;
}

// Which pass produced each (resource, version).
std::map<Version, uint32_t> producers(const GraphDesc& g) {
  std::map<Version, uint32_t> out;
  for (uint32_t p = 0; p < g.passes.size(); ++p)
    for (const ResourceAccess& a : g.passes[p].accesses)
      if (accessInfo(a.access).write) out[{a.resource, a.version + 1}] = p;
  return out;
}

constexpr VkAccessFlags2 kWriteAccesses =
    VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT |
    VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;

}  // namespace

std::vector<bool> cull(const GraphDesc& g) {
  std::map<Version, uint32_t> producer = producers(g);
  std::vector<bool> alive(g.passes.size(), false);
  std::vector<uint32_t> work;
  for (uint32_t p = 0; p < g.passes.size(); ++p)
    if (g.passes[p].sideEffect) work.push_back(p);
  while (!work.empty()) {
    uint32_t p = work.back();
    work.pop_back();
    if (alive[p]) continue;
    alive[p] = true;
    // A pure write does not need what was there before; everything else needs its producer.
    for (const ResourceAccess& a : g.passes[p].accesses) {
      if (!reads(a.access)) continue;
      auto it = producer.find({a.resource, a.version});
      if (it != producer.end() && !alive[it->second]) work.push_back(it->second);
    }
  }
  return alive;
}

std::vector<uint32_t> order(const GraphDesc& g, const std::vector<bool>& alive) {
  const uint32_t n = static_cast<uint32_t>(g.passes.size());
  std::map<Version, uint32_t> producer = producers(g);
  std::map<Version, std::vector<uint32_t>> readers;
  for (uint32_t p = 0; p < n; ++p)
    if (alive[p])
      for (const ResourceAccess& a : g.passes[p].accesses)
        if (reads(a.access)) readers[{a.resource, a.version}].push_back(p);

  std::vector<std::set<uint32_t>> next(n);
  auto edge = [&](uint32_t from, uint32_t to) {
    if (from != to && alive[from]) next[from].insert(to);
  };
  for (uint32_t q = 0; q < n; ++q) {
    if (!alive[q]) continue;
    for (const ResourceAccess& a : g.passes[q].accesses) {
      auto prod = producer.find({a.resource, a.version});
      if (prod != producer.end()) edge(prod->second, q);  // RAW, and WAW for writes
      if (accessInfo(a.access).write)
        for (uint32_t r : readers[{a.resource, a.version}]) edge(r, q);  // WAR
    }
  }

  std::vector<uint32_t> indegree(n, 0);
  for (uint32_t p = 0; p < n; ++p)
    for (uint32_t q : next[p]) ++indegree[q];
  std::priority_queue<uint32_t, std::vector<uint32_t>, std::greater<>> ready;
  for (uint32_t p = 0; p < n; ++p)
    if (alive[p] && indegree[p] == 0) ready.push(p);
  std::vector<uint32_t> result;
  while (!ready.empty()) {
    uint32_t p = ready.top();
    ready.pop();
    result.push_back(p);
    for (uint32_t q : next[p])
      if (--indegree[q] == 0) ready.push(q);
  }
  size_t liveCount = static_cast<size_t>(std::count(alive.begin(), alive.end(), true));
  if (result.size() == liveCount) return result;

  // Walk forward through passes still waiting until one repeats: that loop is the cycle.
  std::vector<int> seenAt(n, -1);
  std::vector<uint32_t> path;
  uint32_t p = 0;
  while (!(alive[p] && indegree[p] > 0)) ++p;
  while (seenAt[p] < 0) {
    seenAt[p] = static_cast<int>(path.size());
    path.push_back(p);
    for (uint32_t q : next[p])
      if (indegree[q] > 0) {
        p = q;
        break;
      }
  }
  std::string names;
  for (size_t i = static_cast<size_t>(seenAt[p]); i < path.size(); ++i)
    names += "'" + g.passes[path[i]].name + "' -> ";
  internalError("frame graph has a cycle: " + names + "'" + g.passes[p].name + "'");
}

std::vector<Lifetime> computeLifetimes(const GraphDesc& g, const std::vector<uint32_t>& ord) {
  std::vector<Lifetime> life(g.resources.size());
  for (int pos = 0; pos < static_cast<int>(ord.size()); ++pos)
    for (const ResourceAccess& a : g.passes[ord[static_cast<size_t>(pos)]].accesses) {
      Lifetime& l = life[a.resource];
      if (l.first < 0) l.first = pos;
      l.last = pos;
    }
  return life;
}

uint64_t MemoryPlan::totalBytes() const {
  uint64_t total = 0;
  for (const MemorySlot& s : slots) total += s.size;
  return total;
}

MemoryPlan assignMemory(const GraphDesc& g, const std::vector<Lifetime>& life,
                        const std::vector<MemoryRequirement>& req) {
  MemoryPlan plan;
  plan.slotOf.assign(g.resources.size(), -1);
  std::vector<uint32_t> transient;
  for (uint32_t r = 0; r < g.resources.size(); ++r)
    if (!g.resources[r].imported && life[r].used()) transient.push_back(r);
  std::stable_sort(transient.begin(), transient.end(),
                   [&](uint32_t a, uint32_t b) { return life[a].first < life[b].first; });

  for (uint32_t r : transient) {
    const MemoryRequirement& m = req[r];
    int best = -1;
    for (int s = 0; s < static_cast<int>(plan.slots.size()); ++s) {
      const MemorySlot& slot = plan.slots[static_cast<size_t>(s)];
      if (slot.kind != g.resources[r].kind || (slot.typeBits & m.typeBits) == 0) continue;
      if (life[slot.residents.back()].last >= life[r].first) continue;  // still in use
      if (best < 0) {
        best = s;
        continue;
      }
      // Prefer the smallest slot that already fits; otherwise the largest one, to grow least.
      const MemorySlot& b = plan.slots[static_cast<size_t>(best)];
      bool fits = slot.size >= m.size, bestFits = b.size >= m.size;
      if ((fits && (!bestFits || slot.size < b.size)) || (!fits && !bestFits && slot.size > b.size))
        best = s;
    }
    if (best < 0) {
      plan.slots.push_back({g.resources[r].kind, 0, 1, ~0u, {}});
      best = static_cast<int>(plan.slots.size()) - 1;
    }
    MemorySlot& slot = plan.slots[static_cast<size_t>(best)];
    slot.size = std::max(slot.size, m.size);
    slot.alignment = std::max(slot.alignment, m.alignment);
    slot.typeBits &= m.typeBits;
    slot.residents.push_back(r);
    plan.slotOf[r] = best;
  }
  return plan;
}

BarrierPlan buildBarriers(const GraphDesc& g, const std::vector<uint32_t>& ord,
                          const MemoryPlan& memory) {
  // What each resource needs the next access to wait for.
  struct Track {
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkPipelineStageFlags2 writeStage = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 writeAccess = VK_ACCESS_2_NONE;
    VkPipelineStageFlags2 readStages = VK_PIPELINE_STAGE_2_NONE;     // reads since the write
    VkPipelineStageFlags2 visibleStages = VK_PIPELINE_STAGE_2_NONE;  // already synchronised
    VkAccessFlags2 visibleAccess = VK_ACCESS_2_NONE;
    bool started = false;
  };
  std::vector<Track> track(g.resources.size());
  for (uint32_t r = 0; r < g.resources.size(); ++r)
    if (g.resources[r].imported) {
      track[r].layout = g.resources[r].initial.layout;
      track[r].writeStage = g.resources[r].initial.writeStage;
      track[r].writeAccess = g.resources[r].initial.writeAccess;
    }

  BarrierPlan plan;
  plan.before.resize(ord.size());
  for (size_t pos = 0; pos < ord.size(); ++pos) {
    for (const ResourceAccess& a : g.passes[ord[pos]].accesses) {
      const ResourceNode& res = g.resources[a.resource];
      const AccessInfo& info = accessInfo(a.access);
      Track& t = track[a.resource];
      if (!t.started && !res.imported && memory.slotOf[a.resource] >= 0) {
        // An aliased resource must wait for whatever used its memory before it.
        const auto& residents =
            memory.slots[static_cast<size_t>(memory.slotOf[a.resource])].residents;
        auto it = std::find(residents.begin(), residents.end(), a.resource);
        if (it != residents.begin()) {
          const Track& prev = track[*(it - 1)];
          t.writeStage = prev.writeStage | prev.readStages;
          t.writeAccess = prev.writeAccess;
        }
      }
      t.started = true;

      const bool image = res.kind == ResourceKind::Image;
      const VkImageLayout layout = image ? info.layout : VK_IMAGE_LAYOUT_UNDEFINED;
      const bool transition = image && t.layout != layout;
      auto emit = [&](VkPipelineStageFlags2 src, VkAccessFlags2 srcAccess, VkImageLayout from) {
        plan.before[pos].push_back(
            {a.resource, src, srcAccess, info.stage, info.access, from, layout});
      };
      if (info.write || transition) {
        VkPipelineStageFlags2 src = t.writeStage | t.readStages;
        if (src != VK_PIPELINE_STAGE_2_NONE || transition) emit(src, t.writeAccess, t.layout);
        t.layout = layout;
        t.writeStage = info.stage;
        // A layout transition on a read behaves like a write nobody else has seen yet.
        t.writeAccess = info.write ? (info.access & kWriteAccesses) : VK_ACCESS_2_NONE;
        t.readStages = info.write ? VK_PIPELINE_STAGE_2_NONE : info.stage;
        t.visibleStages = info.write ? VK_PIPELINE_STAGE_2_NONE : info.stage;
        t.visibleAccess = info.write ? VK_ACCESS_2_NONE : info.access;
      } else {
        bool unseen = (info.stage & ~t.visibleStages) || (info.access & ~t.visibleAccess);
        if (t.writeStage != VK_PIPELINE_STAGE_2_NONE && unseen) {
          emit(t.writeStage, t.writeAccess, layout);
          t.visibleStages |= info.stage;
          t.visibleAccess |= info.access;
        }
        t.readStages |= info.stage;
      }
    }
  }
  plan.finalState.resize(g.resources.size());
  for (uint32_t r = 0; r < g.resources.size(); ++r)
    plan.finalState[r] = {track[r].layout, track[r].writeStage, track[r].writeAccess};
  return plan;
}

}  // namespace sky
