// CPU-only tests of the frame-graph compile stages, on plain GraphDesc data and through the
// real builder (no GPU): culling, ordering, cycles, stale handles, lifetimes, memory reuse
// and the exact barrier list.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "engine/graph/compile.h"
#include "engine/graph/frame_graph.h"

namespace sky {
namespace {

using ::testing::HasSubstr;

ResourceNode image(const std::string& name, uint32_t size = 64) {
  ResourceNode r;
  r.name = name;
  r.image.name = name;
  r.image.width = r.image.height = size;
  return r;
}

PassNode pass(const std::string& name, std::vector<ResourceAccess> accesses,
              bool sideEffect = false) {
  return {name, std::move(accesses), sideEffect};
}

constexpr Access kWrite = Access::StorageWriteCompute;
constexpr Access kSample = Access::SampledCompute;
constexpr Access kCopy = Access::TransferSrc;

// fill -> a -> blur -> b -> readback, plus an unused "debug" pass writing c.
GraphDesc chain() {
  GraphDesc g;
  g.resources = {image("a"), image("b"), image("c")};
  g.passes = {pass("fill", {{0, 0, kWrite}}), pass("debug", {{0, 1, kSample}, {2, 0, kWrite}}),
              pass("blur", {{0, 1, kSample}, {1, 0, kWrite}}),
              pass("readback", {{1, 1, kCopy}}, true)};
  return g;
}

TEST(GraphCull, DropsPassesNoOutputNeeds) {
  EXPECT_EQ(cull(chain()), (std::vector<bool>{true, false, true, true}));
}

TEST(GraphCull, KeepsEverythingAnOutputNeedsTransitively) {
  GraphDesc g = chain();
  g.passes.push_back(pass("dump", {{2, 1, kCopy}}, true));  // now someone wants c
  EXPECT_EQ(cull(g), (std::vector<bool>{true, true, true, true, true}));
}

TEST(GraphCull, NothingRunsWithoutASideEffect) {
  GraphDesc g = chain();
  g.passes.pop_back();
  EXPECT_EQ(cull(g), (std::vector<bool>{false, false, false}));
}

TEST(GraphOrder, FollowsDependenciesAndKeepsDeclarationOrderForTies) {
  GraphDesc g = chain();
  std::vector<bool> alive = cull(g);
  EXPECT_EQ(order(g, alive), (std::vector<uint32_t>{0, 2, 3}));
  std::vector<bool> all(g.passes.size(), true);
  EXPECT_EQ(order(g, all), (std::vector<uint32_t>{0, 1, 2, 3}));
}

TEST(GraphOrder, ReaderOfAnOlderVersionRunsBeforeTheNextWriter) {
  // "late" is declared after "overwrite" but reads the version "overwrite" replaces.
  GraphDesc g;
  g.resources = {image("r"), image("out")};
  g.passes = {pass("fill", {{0, 0, kWrite}}),
              pass("overwrite", {{0, 1, Access::StorageReadWriteCompute}}),
              pass("late", {{0, 1, kSample}, {1, 0, kWrite}}),
              pass("readback", {{0, 2, kCopy}, {1, 1, kCopy}}, true)};
  EXPECT_EQ(order(g, cull(g)), (std::vector<uint32_t>{0, 2, 1, 3}));
}

TEST(GraphOrder, CycleIsAnErrorNamingThePasses) {
  GraphDesc g;
  g.resources = {image("a"), image("b")};
  g.passes = {pass("first", {{1, 1, kSample}, {0, 0, kWrite}}, true),
              pass("second", {{0, 1, kSample}, {1, 0, kWrite}}, true)};
  try {
    order(g, {true, true});
    FAIL() << "expected a cycle error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Internal);
    EXPECT_THAT(e.what(), HasSubstr("cycle"));
    EXPECT_THAT(e.what(), HasSubstr("'first'"));
    EXPECT_THAT(e.what(), HasSubstr("'second'"));
  }
}

TEST(GraphLifetimes, FirstAndLastUseInExecutionOrder) {
  GraphDesc g = chain();
  std::vector<uint32_t> ord = order(g, cull(g));  // fill, blur, readback
  std::vector<Lifetime> life = computeLifetimes(g, ord);
  EXPECT_EQ(life[0], (Lifetime{0, 1}));
  EXPECT_EQ(life[1], (Lifetime{1, 2}));
  EXPECT_FALSE(life[2].used());  // only the culled debug pass touched it
}

TEST(GraphMemory, NonOverlappingTransientsShareASlot) {
  // a (0..1), b (1..2), c (2..3): a and c never live at the same time.
  GraphDesc g;
  g.resources = {image("a"), image("b"), image("c")};
  g.passes = {pass("p0", {{0, 0, kWrite}}), pass("p1", {{0, 1, kSample}, {1, 0, kWrite}}),
              pass("p2", {{1, 1, kSample}, {2, 0, kWrite}}),
              pass("readback", {{2, 1, kCopy}}, true)};
  std::vector<uint32_t> ord = order(g, cull(g));
  std::vector<Lifetime> life = computeLifetimes(g, ord);
  std::vector<MemoryRequirement> req(3, {1000, 256, 0b11});
  req[2].size = 1500;  // c is larger: the shared slot grows to fit it
  MemoryPlan plan = assignMemory(g, life, req);
  ASSERT_EQ(plan.slots.size(), 2u);
  EXPECT_EQ(plan.slotOf, (std::vector<int>{0, 1, 0}));
  EXPECT_EQ(plan.slots[0].residents, (std::vector<uint32_t>{0, 2}));
  EXPECT_EQ(plan.slots[0].size, 1500u);
  EXPECT_EQ(plan.totalBytes(), 2500u);
}

TEST(GraphMemory, NoSharingAcrossKindsMemoryTypesOrImports) {
  GraphDesc g;
  g.resources = {image("a"), image("b"), image("imported")};
  g.resources[2].imported = true;
  g.passes = {pass("p0", {{0, 0, kWrite}}), pass("p1", {{0, 1, kSample}, {2, 0, kWrite}}),
              pass("p2", {{1, 0, kWrite}}), pass("readback", {{1, 1, kCopy}, {2, 1, kCopy}}, true)};
  std::vector<uint32_t> ord = order(g, cull(g));
  std::vector<Lifetime> life = computeLifetimes(g, ord);
  // a and b could share by lifetime, but their memory types have nothing in common.
  std::vector<MemoryRequirement> req = {{100, 16, 0b01}, {100, 16, 0b10}, {100, 16, 0b11}};
  MemoryPlan plan = assignMemory(g, life, req);
  EXPECT_EQ(plan.slots.size(), 2u);
  EXPECT_EQ(plan.slotOf[2], -1);
  req[1].typeBits = 0b11;
  plan = assignMemory(g, life, req);
  EXPECT_EQ(plan.slots.size(), 1u);
  EXPECT_EQ(plan.slots[0].typeBits, 0b01u);
}

TEST(GraphBarriers, ExactListForASmallGraph) {
  // fill -> a -> blur -> b -> tone -> c -> readback, where c reuses a's memory.
  GraphDesc g;
  g.resources = {image("a"), image("b"), image("c")};
  g.passes = {pass("fill", {{0, 0, kWrite}}), pass("blur", {{0, 1, kSample}, {1, 0, kWrite}}),
              pass("tone", {{1, 1, kSample}, {2, 0, kWrite}}),
              pass("readback", {{2, 1, kCopy}}, true)};
  std::vector<uint32_t> ord = order(g, cull(g));
  std::vector<Lifetime> life = computeLifetimes(g, ord);
  MemoryPlan mem = assignMemory(g, life, std::vector<MemoryRequirement>(3, {4096, 256, ~0u}));
  ASSERT_EQ(mem.slotOf, (std::vector<int>{0, 1, 0}));
  BarrierPlan plan = buildBarriers(g, ord, mem);

  constexpr auto C = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  constexpr auto COPY = VK_PIPELINE_STAGE_2_COPY_BIT;
  constexpr auto NONE = VK_PIPELINE_STAGE_2_NONE;
  constexpr auto W = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
  constexpr auto S = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
  constexpr auto UNDEF = VK_IMAGE_LAYOUT_UNDEFINED;
  constexpr auto GEN = VK_IMAGE_LAYOUT_GENERAL;
  constexpr auto RO = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  using B = std::vector<Barrier>;
  ASSERT_EQ(plan.before.size(), 4u);
  EXPECT_EQ(plan.before[0], (B{{0, NONE, 0, C, W, UNDEF, GEN}}));
  EXPECT_EQ(plan.before[1], (B{{0, C, W, C, S, GEN, RO}, {1, NONE, 0, C, W, UNDEF, GEN}}));
  // c takes over a's memory: it waits for a's last use (the sampled read in blur).
  EXPECT_EQ(plan.before[2], (B{{1, C, W, C, S, GEN, RO}, {2, C, 0, C, W, UNDEF, GEN}}));
  EXPECT_EQ(plan.before[3], (B{{2, C, W, COPY, VK_ACCESS_2_TRANSFER_READ_BIT, GEN,
                                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL}}));
}

TEST(GraphBarriers, ImportedStateSynchronisesWithThePreviousFrame) {
  GraphDesc g;
  g.resources = {image("noise"), image("out")};
  g.resources[0].imported = true;
  g.resources[0].initial = {VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
  g.passes = {pass("use", {{0, 0, kSample}, {1, 0, kWrite}}),
              pass("use2", {{0, 0, kSample}, {1, 1, Access::StorageReadWriteCompute}}),
              pass("readback", {{1, 2, kCopy}}, true)};
  std::vector<uint32_t> ord = order(g, cull(g));
  MemoryPlan mem = assignMemory(g, computeLifetimes(g, ord), std::vector<MemoryRequirement>(2));
  BarrierPlan plan = buildBarriers(g, ord, mem);
  // Same layout, but last frame's write must be made visible — once, not per reader.
  ASSERT_EQ(plan.before[0].size(), 2u);
  EXPECT_EQ(plan.before[0][0],
            (Barrier{0, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}));
  for (const Barrier& b : plan.before[1]) EXPECT_NE(b.resource, 0u);
  EXPECT_EQ(plan.finalState[0].layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

// Through the real builder, without a GPU.
TEST(GraphBuilder, StaleHandleIsAnErrorNamingPassAndResource) {
  FrameGraph graph;
  GraphBuilder a = graph.addPass("first", [](PassContext&) {});
  ImageDesc d;
  d.name = "cloud_density";
  ImageId v0 = a.create(d);
  ImageId v1 = a.write(v0, kWrite);
  GraphBuilder b = graph.addPass("second", [](PassContext&) {});
  try {
    b.read(v0, kSample);
    FAIL() << "expected a stale-handle error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("pass 'second'"));
    EXPECT_THAT(e.what(), HasSubstr("stale handle"));
    EXPECT_THAT(e.what(), HasSubstr("'cloud_density'"));
    EXPECT_THAT(e.what(), HasSubstr("'first' wrote version 1"));
  }
  EXPECT_EQ(b.read(v1, kSample), v1);
}

TEST(GraphBuilder, ReadBeforeWriteAndDoubleDeclarationAreErrors) {
  FrameGraph graph;
  GraphBuilder a = graph.addPass("p", [](PassContext&) {});
  ImageId img = a.create(ImageDesc{"img"});
  EXPECT_THROW(a.read(img, kSample), Error);
  ImageId written = a.write(img, kWrite);
  EXPECT_THROW(a.read(written, kSample), Error);  // same resource twice in one pass
}

TEST(GraphBuilder, UsageIsDerivedFromAccessesAndDotNamesEverything) {
  FrameGraph graph;
  ImageId img;
  {
    GraphBuilder a = graph.addPass("fill", [](PassContext&) {});
    img = a.write(a.create(ImageDesc{"img"}), kWrite);
  }
  {
    GraphBuilder unused = graph.addPass("unused", [](PassContext&) {});
    (void)unused.write(unused.create(ImageDesc{"debug"}), kWrite);
  }
  graph.requestOutput(img, "img");
  const CompiledGraph& c = graph.compile();
  EXPECT_EQ(graph.desc().resources[0].image.usage,
            VkImageUsageFlags(VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT));
  EXPECT_EQ(c.alive, (std::vector<bool>{true, false, true}));
  std::string dot = graph.toDot();
  EXPECT_THAT(dot, HasSubstr("digraph frame_graph"));
  EXPECT_THAT(dot, HasSubstr("#0 fill"));
  EXPECT_THAT(dot, HasSubstr("unused\\n(culled)"));
  EXPECT_THAT(dot, HasSubstr("#1 readback"));
  EXPECT_THROW(graph.addPass("late", [](PassContext&) {}), Error);
}

// The debug views' registry is the graph itself: every image by its name, at its last
// version, with the pass that wrote that version; an unknown name lists the known ones.
TEST(GraphImages, EveryImageByNameAtItsLastVersionWithItsWriter) {
  FrameGraph graph;
  ImageDesc d;
  d.name = "marched";
  d.view = DebugView::Heat;
  ImageId marched;
  {
    GraphBuilder a = graph.addPass("march", [](PassContext&) {});
    marched = a.write(a.create(d), kWrite);
  }
  {
    GraphBuilder b = graph.addPass("refine", [](PassContext&) {});
    marched = b.write(marched, kWrite);
  }
  {
    GraphBuilder c = graph.addPass("resolve", [](PassContext&) {});
    c.read(marched, kSample);
    d.name = "resolved";
    d.view = DebugView::Color;
    (void)c.write(c.create(d), kWrite);
  }
  const std::vector<GraphImage> images = graph.images();
  ASSERT_EQ(images.size(), 2u);
  EXPECT_EQ(images[0].name, "marched");
  EXPECT_EQ(images[0].latest, marched);
  EXPECT_EQ(images[0].latest.version, 2u);
  EXPECT_EQ(images[0].writer, "refine");
  EXPECT_EQ(images[0].desc.view, DebugView::Heat);
  EXPECT_EQ(graph.image("resolved").writer, "resolve");
  try {
    graph.image("steps");
    FAIL() << "expected UnknownImageName";
  } catch (const UnknownImageName& e) {
    EXPECT_EQ(e.kind(), ErrorKind::BadInput);
    EXPECT_EQ(e.name(), "steps");
    EXPECT_EQ(e.known(), (std::vector<std::string>{"marched", "resolved"}));
    EXPECT_THAT(e.what(), HasSubstr("'steps'"));
    EXPECT_THAT(e.what(), HasSubstr("marched, resolved"));
  }
}

}  // namespace
}  // namespace sky
