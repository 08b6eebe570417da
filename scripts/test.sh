#!/usr/bin/env bash
# README command 2: install what is missing, build, run every test. ctest sets
# SKY_VALIDATION=1, so the whole suite runs under the Vulkan validation layers and any
# validation message fails the test that caused it. Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${SKY_PRESET:-release}"
./scripts/build.sh "$preset"
ctest --preset "$preset" -j "$(nproc)" "$@"
