#!/usr/bin/env bash
# README command 1: install what is missing, build, render the embedded default scene
# into out/sky.exr, out/sky.png and out/sky.json. Extra arguments go to `skyrender render`.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh release skyrender
./build/release/apps/skyrender/skyrender render --out out "$@"
