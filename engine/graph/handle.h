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

}  // namespace sky
