#!/usr/bin/env bash
# Packs the release build's GPU-facing binaries with the shared libraries a bare machine
# lacks (OCIO, OpenEXR, yaml-cpp, the Vulkan loader, glvnd for NVIDIA's ICD) and the
# validation layer into .gpu-carry/bundle.tar.xz, to run the tests on a real GPU machine
# that has a driver but no packages. On that machine, from the repository root:
#   mkdir -p /tmp/b && tar -C /tmp/b -xJf .gpu-carry/bundle.tar.xz
#   export LD_LIBRARY_PATH=/tmp/b/lib VK_LAYER_PATH=/tmp/b/layers SKY_DATA_DIR=$PWD \
#          SKY_TEST_DATA=$PWD/tests/data SKY_SKYRENDER=/tmp/b/bin/skyrender
#   for t in /tmp/b/bin/test_*; do $t; done
# (NVIDIA: VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json if needed.)
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh release
b=.gpu-bundle
rm -rf "$b" && mkdir -p "$b/bin" "$b/lib" "$b/layers" .gpu-carry
for t in apps/skyrender/skyrender tests/gpu/test_gpu tests/graph/test_graph_gpu tests/passes/test_passes \
         tests/apps/test_skyrender_cli; do
  cp "build/release/$t" "$b/bin/"
done
strip "$b"/bin/*
for f in "$b"/bin/*; do ldd "$f" | awk '/=>/ {print $3}'; done | sort -u |
  grep -vE 'libc\.so|libm\.so|libpthread|libdl\.so|librt\.so|ld-linux|libgcc_s|libstdc\+\+' |
  xargs -I{} cp -L {} "$b/lib/"
tmp=$(mktemp -d)
(cd "$tmp" && apt-get download libglvnd0 libglx0 libgl1 libegl1 libopengl0 >/dev/null)
for d in "$tmp"/*.deb; do dpkg -x "$d" "$tmp/x"; done
cp -P "$tmp"/x/usr/lib/x86_64-linux-gnu/*.so* "$b/lib/"
rm -rf "$tmp"
cp -L /usr/lib/x86_64-linux-gnu/libVkLayer_khronos_validation.so "$b/layers/"
sed 's|"library_path": *"[^"]*"|"library_path": "./libVkLayer_khronos_validation.so"|' \
  /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json > "$b/layers/VkLayer_khronos_validation.json"
strip "$b"/lib/*.so* "$b"/layers/*.so 2>/dev/null || true
tar -C "$b" -cJf .gpu-carry/bundle.tar.xz .
echo "wrote .gpu-carry/bundle.tar.xz ($(du -h .gpu-carry/bundle.tar.xz | cut -f1))"
