#include "engine/core/fault_injection.h"

#include <array>
#include <atomic>
#include <cstdlib>
#include <mutex>
#include <string>

#include "engine/core/error.h"

namespace sky {
namespace {

constexpr std::array<std::pair<FaultPoint, std::string_view>, 3> kNames{{
    {FaultPoint::KillAfterRename, "kill_after_rename"},
    {FaultPoint::DeviceLostAtSubmit, "device_lost_submit"},
    {FaultPoint::OutOfDeviceMemory, "out_of_device_memory"},
}};

struct Fault {
  bool armed = false;
  FaultPoint point{};
  long nth = 1;
};

// SKY_FAULT, parsed once.
const Fault& fault() {
  static const Fault parsed = [] {
    Fault f;
    const char* env = std::getenv("SKY_FAULT");
    if (!env || !*env) return f;
    std::string spec = env;
    const size_t at = spec.find('@');
    const std::string name = spec.substr(0, at);
    if (at != std::string::npos) {
      char* end = nullptr;
      f.nth = std::strtol(spec.c_str() + at + 1, &end, 10);
      if (*end != '\0' || f.nth < 1) inputError("SKY_FAULT=" + spec + ": N in POINT@N must be 1 or more");
    }
    for (const auto& [point, text] : kNames)
      if (name == text) {
        f.point = point;
        f.armed = true;
      }
    if (!f.armed) {
      std::string known;
      for (const auto& [point, text] : kNames) known += (known.empty() ? "" : ", ") + std::string(text);
      inputError("SKY_FAULT=" + spec + ": unknown fault point '" + name + "' (known: " + known + ")");
    }
    return f;
  }();
  return parsed;
}

std::atomic<long> gReached{0};

}  // namespace

bool faultAt(FaultPoint point) {
  const Fault& f = fault();
  if (!f.armed || f.point != point) return false;
  return gReached.fetch_add(1, std::memory_order_relaxed) + 1 == f.nth;
}

}  // namespace sky
