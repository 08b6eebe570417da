#pragma once
// Typed resource handles. A handle names one *version* of a resource: every write returns a
// new version, and using an older one afterwards is an error naming the pass and resource.
#include <cstdint>

namespace sky {

class Image;
class Buffer;

template <class T>
struct Handle {
  static constexpr uint32_t kInvalid = 0xffffffffu;
  uint32_t id = kInvalid;  // index into the graph's resources
  uint32_t version = 0;    // 0 = as created or imported; each write adds one

  bool valid() const { return id != kInvalid; }
  bool operator==(const Handle&) const = default;
};

using ImageId = Handle<Image>;
using BufferId = Handle<Buffer>;

// An output a frame reads back (FrameGraph::requestOutput): its place in the frame's
// FrameResult::outputs, so a renderer finds what it asked for without matching labels.
struct OutputId {
  static constexpr uint32_t kInvalid = 0xffffffffu;
  uint32_t index = kInvalid;

  bool valid() const { return index != kInvalid; }
  bool operator==(const OutputId&) const = default;
};

}  // namespace sky
