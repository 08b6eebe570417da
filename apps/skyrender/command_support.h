#pragma once
// What several skyrender commands share (commands.cpp defines them): the progress bar's line,
// the Vulkan context from --gpu, the cache warning and the high-cloud bake's bar.
#include <functional>
#include <string>

#include "cli_args.h"
#include "engine/gpu/context.h"

namespace sky {

// "\r[#####.....] text" on stderr: one line that redraws itself.
void drawBar(double fraction, const std::string& text);
// The Vulkan context options of the environment (SKY_VALIDATION, ...) with the device the
// command's --gpu picks ("" the default one).
ContextOptions contextOptions(const CliArgs& args);
// Once per process: a warning that the cache folder cannot be written.
void warnIfCacheUnwritable();
// A bar for a high-cloud bake, on a terminal only (Renderer::setBakeProgress).
std::function<void(double)> bakeProgressBar();

}  // namespace sky
