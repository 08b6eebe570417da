#!/usr/bin/env bash
# Re-renders the golden images in tests/golden/ after an intended change to the look.
# Review the new images (e.g. skyrender render configs/tests/<name>.yaml) before committing.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh release
SKY_UPDATE_GOLDEN=1 ctest --preset release -R Golden
