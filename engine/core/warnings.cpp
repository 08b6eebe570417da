#include "engine/core/warnings.h"

#include <cstdio>
#include <mutex>

namespace sky {
namespace {

std::mutex gMutex;

WarningSink& sink() {
  static WarningSink s = [](const std::string& line) {
    std::fprintf(stderr, "warning: %s\n", line.c_str());
  };
  return s;
}

}  // namespace

WarningSink setWarningSink(WarningSink next) {
  std::lock_guard<std::mutex> lock(gMutex);
  WarningSink previous = std::move(sink());
  sink() = std::move(next);
  return previous;
}

void warn(const std::string& line) {
  std::lock_guard<std::mutex> lock(gMutex);
  if (sink()) sink()(line);
}

}  // namespace sky
