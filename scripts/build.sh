#!/usr/bin/env bash
# Installs missing packages, then configures and builds a CMake preset (default: release).
# Usage: scripts/build.sh [PRESET [TARGET...]]   (no target: everything, tests included)
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
shift || true
./scripts/install-deps.sh
cmake --preset "$preset" >/dev/null
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build --preset "$preset" -j "$(nproc)" "${targets[@]}"
