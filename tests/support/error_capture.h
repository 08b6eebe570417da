#pragma once
// Catching sky::Error in tests: the error itself, so a test can check kind and message.
#include <gtest/gtest.h>

#include "engine/core/error.h"

namespace sky::test {

// Runs f and returns the sky::Error it throws; a test failure when it throws none.
template <class F>
Error catchError(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "expected a sky::Error, nothing was thrown";
  return Error(ErrorKind::Internal, "<no error thrown>");
}

}  // namespace sky::test
