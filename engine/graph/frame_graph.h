#pragma once
// The frame graph: passes declare what they read and write in setup; the graph culls,
// orders, allocates transient memory (aliasing where lifetimes allow), derives every
// barrier, records, submits, times each pass and reads requested outputs back.
// A FrameGraph is built for one frame and executed once; GraphRuntime persists.
#include <functional>
#include <initializer_list>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/error.h"
#include "engine/graph/compile.h"
#include "engine/graph/graph_desc.h"
#include "engine/graph/graph_runtime.h"
#include "engine/graph/handle.h"

namespace sky {

class Context;
class FrameGraph;
class GraphRuntime;
class PassContext;
class TimestampPool;

// A resource that outlives frames (baked noise, weather map, LUTs): imported into each
// frame's graph, which keeps `state` current so the next frame synchronises correctly.
struct PersistentImage {
  Image image;
  ResourceState state;
};
struct PersistentBuffer {
  Buffer buffer;
  ResourceState state;
};

// Two images that carry a pass's result from one frame into the next (temporal reuse): each
// frame reads the one the frame before wrote and writes the other (FrameGraph::importHistory).
// Its owner keeps it between frames; a frame's execute() flips it once the frame has run, so
// a frame that fails leaves the last good history in place.
class HistoryImage {
public:
  // (Re)creates both images when `desc` differs from theirs (a new size or format): the
  // history is then empty. Usage: written as storage, sampled, read back.
  void ensure(const Context& ctx, const ImageDesc& desc);
  // Forgets what the images hold (a cut: the camera jumped, a setting changed).
  void invalidate() { mValid = false; }
  // Whether the image a frame reads was written by the frame before.
  bool valid() const { return mValid; }

private:
  friend class FrameGraph;
  PersistentImage mImages[2];
  // The desc's name: a frame names its two images NAME_history (this frame's) and
  // NAME_history_previous (the frame before's).
  std::string mName;
  uint32_t mWrite = 0;  // the image this frame writes; the other one it reads
  bool mValid = false;
};

// A history in one frame's graph: `previous` is last frame's result (undefined unless
// `valid`), `next` the image this frame must write in full (a pass writing it is kept even
// when nothing else reads it this frame: the next frame does).
struct HistoryIds {
  ImageId previous;
  ImageId next;
  bool valid = false;
};

// Handed to a pass's setup; every declaration is attributed to that pass.
class GraphBuilder {
public:
  // A transient image/buffer, created by this pass (its first access must be a write).
  ImageId create(const ImageDesc& desc);
  BufferId create(const BufferDesc& desc);
  // Declares a read; returns the same handle. A stale handle is an error.
  ImageId read(ImageId image, Access access);
  BufferId read(BufferId buffer, Access access);
  // Declares a write (or read-write); returns the new version, the only valid handle after.
  [[nodiscard]] ImageId write(ImageId image, Access access);
  [[nodiscard]] BufferId write(BufferId buffer, Access access);
  // Keeps the pass even when nothing reads its results.
  void sideEffect();

private:
  friend class FrameGraph;
  GraphBuilder(FrameGraph& graph, uint32_t pass) : mGraph(graph), mPass(pass) {}
  FrameGraph& mGraph;
  uint32_t mPass;
};

struct PassTiming {
  std::string name;
  double gpuMs = 0.0;
  // Texels of the largest image the pass writes (width x height x depth; 0 for a pass that
  // writes only buffers): the size a benchmark compares the pass with (an empty full-screen
  // pass of as many pixels, benchmarks/README.md).
  uint64_t texels = 0;
};

struct ReadbackImage {
  std::string label;
  uint32_t width = 0, height = 0, depth = 1, channels = 0;
  VkFormat format = VK_FORMAT_UNDEFINED;
  std::vector<float> pixels;  // interleaved, row 0 = top
};

struct FrameResult {
  std::vector<PassTiming> passes;  // in execution order, culled passes absent
  double gpuMs = 0.0;              // sum of the passes' GPU time
  double wallMs = 0.0;             // record + submit + wait + readback, on the CPU clock
  std::vector<ReadbackImage> outputs;
  // The output requested under `label`; Internal error if there is none.
  const ReadbackImage& output(std::string_view label) const;
  // The output requestOutput returned `id` for; Internal error if it is not this frame's.
  const ReadbackImage& output(OutputId id) const;
  ReadbackImage& output(OutputId id);
};

// An image of a frame's graph, as a debug view finds it: by its name (ImageDesc::name).
// A buffer that holds an image (BufferDesc::image) is one too, shown as an R32F image.
struct GraphImage {
  std::string name;
  ImageId latest;      // its last version in the graph: what the frame ends up holding
  BufferId buffer;     // instead of `latest`, for a buffer that holds an image
  std::string writer;  // the pass that wrote that version; "" for an imported image no pass
                       // of this frame writes (uploaded, baked or kept from an earlier frame)
  ImageDesc desc;      // the image's; a buffer's image as its BufferImage says
};

// A name no image of the graph has. BadInput: names come from users (--debug-output, the
// window's debug view); what() names it and lists the graph's images.
class UnknownImageName : public Error {
public:
  UnknownImageName(std::string name, std::vector<std::string> known);
  const std::string& name() const { return mName; }
  const std::vector<std::string>& known() const { return mKnown; }

private:
  std::string mName;
  std::vector<std::string> mKnown;
};

struct CompiledGraph {
  std::vector<bool> alive;
  std::vector<uint32_t> order;
  std::vector<Lifetime> lifetimes;
  MemoryPlan memory;
  BarrierPlan barriers;
};

class FrameGraph {
public:
  explicit FrameGraph(GraphRuntime& runtime, GraphUse use = GraphUse::Frame);
  // A graph without a GPU: it can be built, compiled (memory sizes estimated from texel
  // counts) and dumped, but not executed. For tests and tools.
  FrameGraph();
  ~FrameGraph();

  ImageId importImage(PersistentImage& image);
  // Imports both images of `history` (see HistoryImage); ensure() it first.
  HistoryIds importHistory(HistoryImage& history);
  BufferId importBuffer(PersistentBuffer& buffer);
  // An image the host owns, for this frame (skylayers::Sky::record; `image` borrows it): the
  // frame finds it in `hostLayout` after any host work before, waits for all of that, and
  // leaves it in `hostLayout` again with its writes made available to any host work after.
  ImageId importExternal(PersistentImage& image, VkImageLayout hostLayout);
  // A transfer pass `name` that fills the whole of `image` with `pixels`: interleaved floats,
  // formatChannelCount per texel, row 0 the top, converted to the image's format (rgba16f,
  // rgba32f, r16f, r32f, r8, rgba8 unorm). The texels are staged at once in a host-visible
  // buffer that the graph frees after execute(). The pass is kept though nothing in this frame
  // reads the image (later frames do). Returns the image's new version. Internal error for a
  // count of values that is not the image's, or an image without TRANSFER_DST usage.
  [[nodiscard]] ImageId upload(ImageId image, std::span<const float> pixels, std::string name);
  // The same with `texels` already in the image's format (formatTexelSize bytes each), copied
  // as they are: a cache of 8-bit noise skips two conversions of every value.
  [[nodiscard]] ImageId uploadTexels(ImageId image, std::span<const uint8_t> texels,
                                     std::string name);
  // Calls `done` once execute() has run this frame to its end. An owner of a persistent image
  // learns that what the frame wrote there (an upload) landed: a frame that fails, or a graph
  // never executed, calls nothing, and the owner tries again next frame.
  void afterExecute(std::function<void()> done);
  // Adds a pass; declare its resources through the returned builder before adding the next.
  GraphBuilder addPass(std::string name, std::function<void(PassContext&)> execute);
  // Adds a pass object (see STYLE.md): P::kName, P::Inputs, P::Outputs, setup(), execute().
  // The pass object must outlive execute(). A pass with a P::Data keeps what one use of it
  // needs at execute() there, owned by the graph (setup(builder, inputs, data) fills it,
  // execute(ctx, data) reads it), so one pass object can be added several times to a frame:
  // once per view. One without keeps it in itself, and can be added once.
  template <class P>
  typename P::Outputs add(P& pass, const typename P::Inputs& inputs) {
    if constexpr (requires { typename P::Data; }) {
      auto data = std::make_shared<typename P::Data>();
      GraphBuilder b =
          addPass(P::kName, [&pass, data](PassContext& ctx) { pass.execute(ctx, *data); });
      return pass.setup(b, inputs, *data);
    } else {
      GraphBuilder b = addPass(P::kName, [&pass](PassContext& ctx) { pass.execute(ctx); });
      return pass.setup(b, inputs);
    }
  }
  // Prefixes the names of the images and buffers passes create from now on ("view1/": a
  // frame of several views, whose passes would otherwise name theirs alike); "" for none.
  void setNamePrefix(std::string prefix) { mNamePrefix = std::move(prefix); }
  // Reads `image` back to the host after the frame under `label` (main image, AOVs, debug;
  // the label names it in errors and dumps). Returns its handle in FrameResult::output.
  OutputId requestOutput(ImageId image, std::string label);
  // The same for an image images() found: an image, or a buffer that holds one (read back
  // as R32F, each value times its BufferImage::scale).
  OutputId requestOutput(const GraphImage& image, std::string label);
  // Every image added so far, in the order they were added (the debug views' registry: any
  // image a pass declares can be requested by its name, with nothing added for it).
  std::vector<GraphImage> images() const;
  // The image named `name`; UnknownImageName when there is none.
  GraphImage image(std::string_view name) const;

  const GraphDesc& desc() const { return mDesc; }
  // Runs the compile stages; idempotent. Nothing may be added afterwards.
  const CompiledGraph& compile();
  // Compiles if needed, records, submits, waits and reads back. Once per graph.
  FrameResult execute();
  // Compiles if needed and records the frame into `cmd`, the host's command buffer in the
  // recording state, without submitting it (skylayers::Sky::record). Nothing is read back and
  // nothing timed (the passes' gpuMs are 0). The host must submit `cmd`, and it must have
  // completed before the runtime records or executes its next frame: the descriptors,
  // uniforms, transient images and upload staging the frame uses are reused then. Once per
  // graph; a graph with requested outputs is an internal error.
  FrameResult record(VkCommandBuffer cmd);
  // Graphviz text of the graph (compiled: order, culled passes, memory slots, timings).
  std::string toDot(const FrameResult* timings = nullptr) const;

private:
  friend class GraphBuilder;
  friend class PassContext;
  struct PassRecord {
    std::function<void(PassContext&)> execute;
  };
  struct ResourceRecord {
    PersistentImage* image = nullptr;  // imported
    PersistentBuffer* buffer = nullptr;
    int lastWriter = -1;  // pass that wrote the current version (for stale-handle messages)
  };
  uint32_t declare(uint32_t pass, uint32_t resource, uint32_t version, Access access,
                   ResourceKind kind);
  uint32_t addResource(ResourceNode node, ResourceRecord record);
  // execute() and record(): the transient memory for this graph's shape (kept from the
  // frame before when the shape is the same).
  void allocateTransients();
  // execute() and record(): the passes and their barriers into `cmd`, timed when `timestamps`.
  void recordPasses(VkCommandBuffer cmd, TimestampPool* timestamps);
  // After the frame ran or was recorded: the persistent states, histories and uploads.
  void finishFrame();

  GraphRuntime* mRuntime = nullptr;
  GraphUse mUse = GraphUse::Frame;
  GraphDesc mDesc;
  std::vector<PassRecord> mPasses;
  std::vector<ResourceRecord> mResources;
  struct Output {
    uint32_t resource = 0, version = 0;
    std::string label;
  };
  std::vector<Output> mOutputs;
  std::vector<HistoryImage*> mHistories;  // flipped after execute
  std::string mNamePrefix;                // setNamePrefix
  struct External {
    uint32_t resource = 0;
    VkImageLayout hostLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  };
  std::vector<External> mExternals;  // importExternal's, returned to the host's layout
  std::vector<std::unique_ptr<Buffer>> mStaging;  // upload()'s texels, until execute ends
  std::vector<std::function<void()>> mAfterExecute;
  std::optional<CompiledGraph> mCompiled;
  bool mExecuted = false;
};

// One persistent image and the texels to fill it with: floats (FrameGraph::upload's layout),
// or, when `texels` is not empty, bytes in the image's format (FrameGraph::uploadTexels).
struct ImageFill {
  PersistentImage* image;
  std::span<const float> pixels;
  std::span<const uint8_t> texels = {};
};
// Fills persistent images outside a frame (textures loaded from files or a cache): one graph
// (GraphUse::Bake) of passes "upload NAME", executed before this returns.
FrameResult uploadNow(GraphRuntime& runtime, std::initializer_list<ImageFill> fills);

}  // namespace sky
