#pragma once
// GPU tests share one Context per test executable. Every Vulkan validation message it
// reports becomes a failure of the test that is running (ADD_FAILURE from the callback,
// which runs on the thread making the Vulkan call), so the suite is validation-clean or red.
#include <gtest/gtest.h>

#include "engine/gpu/context.h"

namespace sky::test {

// Created on first use with validation from $SKY_VALIDATION (ctest sets it to 1).
Context& sharedContext();
// Destroys the shared context; returns non-zero if validation complained while doing so.
int shutdownSharedContext();

class GpuTest : public ::testing::Test {
protected:
  Context& ctx() { return sharedContext(); }
};

}  // namespace sky::test
