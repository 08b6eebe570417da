#pragma once
// Warnings from library code (a clamped forecast value, a missing field): one line each,
// handed to a sink the application chose instead of written to std::cerr, so a window can
// show them and a host program can log them its own way. Until an app sets one, the sink
// writes "warning: LINE" to stderr.
#include <functional>
#include <string>

namespace sky {

using WarningSink = std::function<void(const std::string& line)>;

// Replaces the process's sink; returns the one it replaces. Thread-safe.
WarningSink setWarningSink(WarningSink sink);
// Hands `line` (no "warning: " prefix, no newline) to the sink. Thread-safe.
void warn(const std::string& line);

}  // namespace sky
