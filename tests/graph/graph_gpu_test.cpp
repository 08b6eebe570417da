// The frame graph on a real device (lavapipe in CI) under validation: aliasing transients,
// derived barriers, culling, timestamps, persistent resources across frames.
#include <cstdlib>

#include <gtest/gtest.h>
#include <gmock/gmock.h>

#include "engine/gpu/compute_pipeline.h"
#include "engine/gpu/sampler.h"
#include "engine/graph/frame_graph.h"
#include "engine/graph/graph_runtime.h"
#include "engine/graph/pass_context.h"
#include "engine/shader/shader_compiler.h"
#include "gpu_test.h"

namespace sky {
namespace {

using ::testing::HasSubstr;

class GraphGpuTest : public test::GpuTest {
protected:
  void SetUp() override {
    ShaderCompiler compiler(std::filesystem::path(std::getenv("SKY_TEST_DATA")) / "graph",
                            std::nullopt);
    CompiledShader fill = compiler.compile("fill.comp");
    CompiledShader add = compiler.compile("add.comp");
    mFill = std::make_unique<ComputePipeline>(ctx(), "fill", fill.spirv, fill.reflection);
    mAdd = std::make_unique<ComputePipeline>(ctx(), "add", add.spirv, add.reflection);
    mSampler = std::make_unique<Sampler>(ctx(), SamplerWrap::Clamp, false);
  }

  static ImageDesc desc(const std::string& name) {
    ImageDesc d;
    d.name = name;
    d.format = VK_FORMAT_R32_SFLOAT;
    d.width = 16;
    d.height = 16;
    return d;
  }

  std::unique_ptr<ComputePipeline> mFill, mAdd;
  std::unique_ptr<Sampler> mSampler;
};

TEST_F(GraphGpuTest, ChainWithAliasedMemoryGivesTheRightPixels) {
  GraphRuntime runtime(ctx());
  FrameGraph g(runtime);
  // Handles captured by the execute lambdas must outlive execute(): keep them here.
  ImageId a, b, c, d;
  {
    GraphBuilder pb = g.addPass("fill", [&](PassContext& pc) {
      float v = 1.0f;
      pc.dispatch(*mFill, {Binding::of(0, a)}, 2, 2, 1, &v, sizeof v);
    });
    a = pb.write(pb.create(desc("a")), Access::StorageWriteCompute);
  }
  auto add = [&](const char* name, ImageId& in, ImageId& out, float v) {
    GraphBuilder pb = g.addPass(name, [&, v](PassContext& pc) {
      pc.dispatch(*mAdd, {Binding::of(0, in, mSampler.get()), Binding::of(1, out)}, 2, 2, 1, &v,
                  sizeof v);
    });
    pb.read(in, Access::SampledCompute);
    out = pb.write(pb.create(desc(std::string(name) + "_out")), Access::StorageWriteCompute);
  };
  add("add1", a, b, 10.0f);    // b = 11
  add("add2", b, c, 100.0f);   // c = 111, may reuse a's memory
  add("add3", c, d, 1000.0f);  // d = 1111, may reuse b's memory
  g.requestOutput(d, "d");
  const CompiledGraph& compiled = g.compile();
  EXPECT_EQ(compiled.memory.slots.size(), 2u) << "4 images with chained lifetimes need 2 slots";
  FrameResult r = g.execute();
  const ReadbackImage& out = r.output("d");
  ASSERT_EQ(out.pixels.size(), 16u * 16u);
  for (float v : out.pixels) ASSERT_FLOAT_EQ(v, 1111.0f);
  EXPECT_EQ(runtime.transientBytes(), compiled.memory.totalBytes());

  ASSERT_EQ(r.passes.size(), 5u);
  EXPECT_EQ(r.passes[0].name, "fill");
  EXPECT_EQ(r.passes[4].name, "readback");
  for (const PassTiming& t : r.passes) EXPECT_GE(t.gpuMs, 0.0);
  if (ctx().hasTimestamps()) {
    EXPECT_GT(r.gpuMs, 0.0);
  }
}

TEST_F(GraphGpuTest, CulledPassesAreNotRecorded) {
  GraphRuntime runtime(ctx());
  FrameGraph g(runtime);
  bool debugRan = false;
  ImageId a, dbg;
  {
    GraphBuilder pb = g.addPass("fill", [&](PassContext& pc) {
      float v = 2.0f;
      pc.dispatch(*mFill, {Binding::of(0, a)}, 2, 2, 1, &v, sizeof v);
    });
    a = pb.write(pb.create(desc("a")), Access::StorageWriteCompute);
  }
  {
    GraphBuilder pb = g.addPass("debug", [&](PassContext&) { debugRan = true; });
    pb.read(a, Access::SampledCompute);
    dbg = pb.write(pb.create(desc("debug")), Access::StorageWriteCompute);
  }
  g.requestOutput(a, "a");
  FrameResult r = g.execute();
  EXPECT_FALSE(debugRan);
  EXPECT_EQ(r.passes.size(), 2u);
  EXPECT_FLOAT_EQ(r.output("a").pixels[0], 2.0f);
}

TEST_F(GraphGpuTest, PersistentImageCarriesDataAndStateAcrossFrames) {
  GraphRuntime runtime(ctx());
  PersistentImage baked;
  ImageDesc d = desc("baked");
  d.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  baked.image = Image(ctx(), d);
  for (int frame = 0; frame < 3; ++frame) {
    FrameGraph g(runtime);
    ImageId in = g.importImage(baked), out;
    if (frame == 0) {
      GraphBuilder pb = g.addPass("bake", [&](PassContext& pc) {
        float v = 5.0f;
        pc.dispatch(*mFill, {Binding::of(0, in)}, 2, 2, 1, &v, sizeof v);
      });
      in = pb.write(in, Access::StorageWriteCompute);
    }
    GraphBuilder pb = g.addPass("use", [&](PassContext& pc) {
      float v = 1.0f;
      pc.dispatch(*mAdd, {Binding::of(0, in, mSampler.get()), Binding::of(1, out)}, 2, 2, 1, &v,
                  sizeof v);
    });
    pb.read(in, Access::SampledCompute);
    out = pb.write(pb.create(desc("out")), Access::StorageWriteCompute);
    g.requestOutput(out, "out");
    FrameResult r = g.execute();
    EXPECT_FLOAT_EQ(r.output("out").pixels[7], 6.0f) << "frame " << frame;
    EXPECT_EQ(r.passes.front().name, frame == 0 ? "bake" : "use");
    EXPECT_EQ(baked.state.layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  }
}

// Temporal reuse's history: each frame reads what the frame before wrote (a running sum),
// the history is empty until a frame has run, and a frame that never executes leaves it.
TEST_F(GraphGpuTest, HistoryCarriesEachFramesResultIntoTheNext) {
  GraphRuntime runtime(ctx());
  HistoryImage history;
  history.ensure(ctx(), desc("sum"));
  EXPECT_FALSE(history.valid());
  for (int frame = 0; frame < 4; ++frame) {
    FrameGraph g(runtime);
    const HistoryIds ids = g.importHistory(history);
    EXPECT_EQ(ids.valid, frame > 0);
    ImageId out;
    GraphBuilder pb = g.addPass("accumulate", [&](PassContext& pc) {
      // The first frame starts from 0 (fill), the others add 1 to last frame's sum.
      float v = ids.valid ? 1.0f : 0.0f;
      if (ids.valid)
        pc.dispatch(*mAdd, {Binding::of(0, ids.previous, mSampler.get()), Binding::of(1, out)}, 2,
                    2, 1, &v, sizeof v);
      else
        pc.dispatch(*mFill, {Binding::of(0, out)}, 2, 2, 1, &v, sizeof v);
    });
    if (ids.valid) pb.read(ids.previous, Access::SampledCompute);
    out = pb.write(ids.next, Access::StorageWriteCompute);
    pb.sideEffect();
    g.requestOutput(out, "sum");
    const FrameResult r = g.execute();
    EXPECT_FLOAT_EQ(r.output("sum").pixels[5], static_cast<float>(frame)) << "frame " << frame;
    EXPECT_TRUE(history.valid());
  }
  {
    FrameGraph unexecuted(runtime);
    unexecuted.importHistory(history);
  }
  FrameGraph g(runtime);
  const HistoryIds ids = g.importHistory(history);
  ImageId out;
  GraphBuilder pb = g.addPass("read", [&](PassContext& pc) {
    float v = 0.0f;
    pc.dispatch(*mAdd, {Binding::of(0, ids.previous, mSampler.get()), Binding::of(1, out)}, 2, 2,
                1, &v, sizeof v);
  });
  pb.read(ids.previous, Access::SampledCompute);
  out = pb.write(pb.create(desc("out")), Access::StorageWriteCompute);
  g.requestOutput(out, "out");
  EXPECT_FLOAT_EQ(g.execute().output("out").pixels[5], 3.0f)
      << "a graph that never ran must not flip the history";
  history.invalidate();
  EXPECT_FALSE(history.valid());
  history.ensure(ctx(), desc("sum"));
  EXPECT_FALSE(history.valid()) << "ensure() with the same shape keeps the images, not validity";
}

// A bake (GraphUse::Bake) runs in its own memory and frees it: the frames around it keep
// theirs, so the frame after a bake allocates nothing.
TEST_F(GraphGpuTest, BakesDoNotEvictTheFramesTransientMemory) {
  GraphRuntime runtime(ctx());
  auto frame = [&](GraphUse use, float value, uint32_t size) {
    FrameGraph g(runtime, use);
    ImageId a;
    GraphBuilder pb = g.addPass("fill", [&](PassContext& pc) {
      pc.dispatch(*mFill, {Binding::of(0, a)}, size / 8, size / 8, 1, &value, sizeof value);
    });
    ImageDesc d = desc("a");
    d.width = d.height = size;
    a = pb.write(pb.create(d), Access::StorageWriteCompute);
    g.requestOutput(a, "a");
    return g.execute().output("a").pixels[3];
  };
  EXPECT_FLOAT_EQ(frame(GraphUse::Frame, 1.0f, 16), 1.0f);
  const uint64_t bytes = runtime.transientBytes();
  EXPECT_EQ(runtime.transientAllocations(), 1u);
  EXPECT_FLOAT_EQ(frame(GraphUse::Bake, 2.0f, 64), 2.0f);  // another shape
  EXPECT_FLOAT_EQ(frame(GraphUse::Frame, 3.0f, 16), 3.0f);
  EXPECT_EQ(runtime.transientAllocations(), 1u) << "the bake evicted the frame's memory";
  EXPECT_EQ(runtime.transientBytes(), bytes);
}

TEST_F(GraphGpuTest, UndeclaredResourceInExecuteIsAnError) {
  GraphRuntime runtime(ctx());
  FrameGraph g(runtime);
  ImageId a, b;
  {
    GraphBuilder pb = g.addPass("fill", [&](PassContext& pc) {
      float v = 1.0f;
      pc.dispatch(*mFill, {Binding::of(0, a)}, 2, 2, 1, &v, sizeof v);
    });
    a = pb.write(pb.create(desc("a")), Access::StorageWriteCompute);
  }
  {
    GraphBuilder pb = g.addPass("sneaky", [&](PassContext& pc) { (void)pc.image(a); });
    b = pb.write(pb.create(desc("b")), Access::StorageWriteCompute);
  }
  g.requestOutput(b, "b");
  g.requestOutput(a, "a");
  try {
    g.execute();
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("pass 'sneaky' uses 'a' without declaring it"));
  }
}

TEST_F(GraphGpuTest, DispatchChecksBindingsAgainstTheShader) {
  GraphRuntime runtime(ctx());
  FrameGraph g(runtime);
  ImageId a;
  GraphBuilder pb = g.addPass("fill", [&](PassContext& pc) {
    float v = 1.0f;
    pc.dispatch(*mFill, {}, 2, 2, 1, &v, sizeof v);  // binding 0 missing
  });
  a = pb.write(pb.create(desc("a")), Access::StorageWriteCompute);
  g.requestOutput(a, "a");
  try {
    g.execute();
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("binding 0 ('outImage') given 0 times"));
  }
}

}  // namespace
}  // namespace sky
