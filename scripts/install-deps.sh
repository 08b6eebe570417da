#!/usr/bin/env bash
# Installs the Debian 12 packages skylayers needs, only those that are missing.
# Usage: scripts/install-deps.sh [--pathtracer] [--peer]
#   --pathtracer  also installs Blender (Cycles) and the Python modules of OpenVDB,
#                 OpenImageIO, YAML and SciPy, which only the path-traced cloud comparison
#                 (scripts/pathtrace/compare.sh) needs; CI and the build never do, and
#                 Blender pulls in some 500 MB.
#   --peer        also installs Chromium, which only the benchmark harness's peer
#                 mode needs (benchmarks/run.py runs ../shared/peers/takram in headless
#                 Chromium with the machine's Node.js; its run.sh takes its npm packages).
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config git
  mesa-vulkan-drivers libvulkan-dev vulkan-tools vulkan-validationlayers
  glslang-dev glslang-tools spirv-tools
  libglm-dev libglfw3-dev libopenexr-dev libopencolorio-dev opencolorio-tools
  libyaml-cpp-dev nlohmann-json3-dev libeccodes-dev libnetcdf-dev
  # libeccodes-dev's CMake package (eccodes-targets.cmake) imports the command-line tools
  # (codes_info, grib_dump, ...) and fails find_package() when /usr/bin/codes_info is
  # absent, but Debian does not make it depend on the package that ships them.
  libeccodes-tools
  libgtest-dev libgmock-dev libbenchmark-dev libstb-dev
  # OpenVDB writes the cloud density grid of `skyrender export-volume` (engine/io/vdb.h).
  # Its headers include Boost's (numeric conversion, ...), which Debian does not make the
  # package depend on.
  libopenvdb-dev libboost-dev
  # The benchmark harness (benchmarks/run.py) is Python; its plots are matplotlib's. CI runs
  # its smoke configuration, plots included.
  python3 python3-matplotlib
  # The Python module (python/, `import skylayers`) is pybind11's; its arrays are numpy's and
  # its tests pytest's.
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest
  # skyview's panel is Dear ImGui (Debian's 1.86); its tests open the window under Xvfb.
  # xvfb-run needs xauth, which xvfb only recommends (a fresh machine without it failed the
  # harness's window smoke test: "xvfb-run: error: xauth command not found").
  libimgui-dev xvfb xauth
  # Datasets on a cluster (docs/datasets.md): the `cluster` ctest case
  # (tests/cluster/slurm_dataset_test.sh) starts a one-node Slurm cluster on loopback with
  # scripts/slurm/local-cluster.sh, which needs the daemons, the client commands and munge.
  slurm-wlm slurm-client munge
  # GNU parallel runs the shards of a dataset on one machine without a scheduler.
  parallel
)
for arg in "$@"; do
  case "$arg" in
    # The field comparison (issue 46) reads skyrender's settings (YAML) and fills the air in
    # front of the clouds from the nearest pixel (scipy.ndimage).
    --pathtracer) PACKAGES+=(blender python3-openvdb python3-openimageio python3-yaml python3-scipy) ;;
    --peer) PACKAGES+=(chromium) ;;
    *) echo "error: install-deps.sh: unknown option '$arg' (expected --pathtracer or --peer)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "installing: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "error: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
