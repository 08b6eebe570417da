#!/usr/bin/env bash
# Installs the Debian 12 packages skylayers needs, only those that are missing.
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
)

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
