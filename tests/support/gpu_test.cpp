#include "gpu_test.h"

#include <iostream>
#include <memory>

namespace sky::test {
namespace {
std::unique_ptr<Context> gContext;
bool gShuttingDown = false;
int gShutdownMessages = 0;
}  // namespace

Context& sharedContext() {
  if (!gContext) {
    ContextOptions options = ContextOptions::fromEnvironment();
    options.onValidationMessage = [](std::string_view message) {
      if (gShuttingDown) {
        ++gShutdownMessages;
        std::cerr << "Vulkan validation (at shutdown): " << message << "\n";
      } else {
        ADD_FAILURE() << "Vulkan validation: " << message;
      }
    };
    gContext = std::make_unique<Context>(options);
  }
  return *gContext;
}

int shutdownSharedContext() {
  gShuttingDown = true;
  gContext.reset();
  return gShutdownMessages ? 1 : 0;
}

}  // namespace sky::test
