// FrameGraph::toDot: the compiled graph as Graphviz, the first debugging tool (--dump-graph).
#include <sstream>

#include "engine/graph/frame_graph.h"

namespace sky {
namespace {

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

std::string FrameGraph::toDot(const FrameResult* timings) const {
  std::ostringstream o;
  o << "digraph frame_graph {\n  rankdir=LR;\n  node [fontname=\"Helvetica\", fontsize=10];\n";
  std::vector<int> position(mDesc.passes.size(), -1);
  if (mCompiled)
    for (size_t i = 0; i < mCompiled->order.size(); ++i)
      position[mCompiled->order[i]] = static_cast<int>(i);

  for (size_t p = 0; p < mDesc.passes.size(); ++p) {
    const PassNode& pass = mDesc.passes[p];
    std::string label = escape(pass.name);
    bool culled = mCompiled && !mCompiled->alive[p];
    if (position[p] >= 0) {
      label = "#" + std::to_string(position[p]) + " " + label;
      if (timings)
        for (const PassTiming& t : timings->passes)
          if (t.name == pass.name) {
            std::ostringstream ms;
            ms.precision(3);
            ms << std::fixed << t.gpuMs;
            label += "\\n" + ms.str() + " ms";
          }
      if (!mCompiled->barriers.before[static_cast<size_t>(position[p])].empty())
        label +=
            "\\n" +
            std::to_string(mCompiled->barriers.before[static_cast<size_t>(position[p])].size()) +
            " barrier(s)";
    }
    if (culled) label += "\\n(culled)";
    o << "  p" << p << " [shape=box, style=\"" << (culled ? "dashed" : "rounded,filled")
      << "\", fillcolor=\"#dde8f5\", color=\"" << (culled ? "gray" : "black") << "\", label=\""
      << label << "\"];\n";
  }
  for (size_t r = 0; r < mDesc.resources.size(); ++r) {
    const ResourceNode& res = mDesc.resources[r];
    std::string label = escape(res.name) + "\\n";
    if (res.kind == ResourceKind::Image) {
      label += std::string(formatName(res.image.format)) + " " + std::to_string(res.image.width) +
               "x" + std::to_string(res.image.height);
      if (res.image.dim == ImageDim::Tex3D) label += "x" + std::to_string(res.image.depth);
    } else {
      label += "buffer " + std::to_string(res.buffer.size) + " B";
    }
    if (res.imported)
      label += "\\nimported";
    else if (mCompiled && mCompiled->memory.slotOf[r] >= 0)
      label += "\\nmemory slot " + std::to_string(mCompiled->memory.slotOf[r]);
    o << "  r" << r << " [shape=" << (res.kind == ResourceKind::Image ? "ellipse" : "cylinder")
      << ", style=filled, fillcolor=\"" << (res.imported ? "#f5e6c8" : "#e4f2df") << "\", label=\""
      << label << "\"];\n";
  }
  for (size_t p = 0; p < mDesc.passes.size(); ++p)
    for (const ResourceAccess& a : mDesc.passes[p].accesses) {
      const AccessInfo& info = accessInfo(a.access);
      if (info.write)
        o << "  p" << p << " -> r" << a.resource << " [label=\"" << info.name << " v"
          << a.version + 1 << "\", color=\"#b03030\"];\n";
      else
        o << "  r" << a.resource << " -> p" << p << " [label=\"" << info.name << " v" << a.version
          << "\"];\n";
    }
  o << "}\n";
  return o.str();
}

}  // namespace sky
