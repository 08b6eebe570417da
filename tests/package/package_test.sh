#!/bin/sh
# The installed package as a user meets it (issue 33, 1): `cmake --install` into a fresh
# prefix, an out-of-tree CMake project that finds it with find_package and renders through
# <skylayers/skylayers.h>, the installed skyrender run from another folder, and the installed
# Python module. None may reach the source tree: SKY_DATA_DIR is unset, so the data must come
# from the prefix.
# Usage: package_test.sh CMAKE BUILD_DIR SOURCE_DIR PYTHON
set -eu
cmake=$1
build=$2
source=$3
python=$4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
work=$(cd "$work" && pwd -P)
prefix=$work/prefix

fail() {
  echo "package_test: $*" >&2
  exit 1
}
run() {  # a step's output only when it fails
  log=$work/step.log
  "$@" >"$log" 2>&1 || { cat "$log" >&2; fail "failed: $*"; }
}

run "$cmake" --install "$build" --prefix "$prefix"
for f in include/skylayers/skylayers.h share/skylayers/shaders/volumetric_clouds.comp \
  share/skylayers/configs/ocio/config.ocio share/skylayers/configs/stars/bright_star_catalogue.txt \
  share/skylayers/configs/default.yaml bin/skyrender; do
  [ -e "$prefix/$f" ] || fail "the install lacks $f"
done
[ -e "$prefix/share/skylayers/configs/tests" ] && fail "the install carries the test scenes"
config=$(find "$prefix" -name skylayersConfig.cmake)
[ -n "$config" ] || fail "the install lacks skylayersConfig.cmake"
find "$prefix" -name 'libskylayers.so*' | grep -q . || fail "the install lacks libskylayers.so"

unset SKY_DATA_DIR SKY_SHADER_DIR
run "$cmake" -S "$source/tests/package/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_BUILD_TYPE=Release
run "$cmake" --build "$work/consumer"
(cd "$work" && "$work/consumer/consumer") >"$work/consumer.txt" 2>&1 ||
  { cat "$work/consumer.txt" >&2; fail "the consumer failed"; }
cat "$work/consumer.txt"
grep -qx "data $prefix/share/skylayers" "$work/consumer.txt" ||
  fail "the library did not read its data from the prefix"
grep -qx "image 24x16 channels 4 display 1536 sum .*" "$work/consumer.txt" || fail "the frame"
grep -q "^error bad_input: set camera.latitud=10: unknown key" "$work/consumer.txt" || fail "the wrong key's error"

(cd "$work" && "$prefix/bin/skyrender" render --width 24 --height 16 --out "$work/out") \
  >"$work/skyrender.txt" 2>&1 || { cat "$work/skyrender.txt" >&2; fail "installed skyrender"; }
ls "$work"/out/*.exr >/dev/null 2>&1 || fail "installed skyrender wrote no EXR"
# The headless example (examples/headless), as its README comment builds it.
run "$cmake" -S "$source/examples/headless" -B "$work/headless" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_BUILD_TYPE=Release
run "$cmake" --build "$work/headless"
(cd "$work" && "$work/headless/headless" "$work/sunset.png") >"$work/headless.txt" 2>&1 ||
  { cat "$work/headless.txt" >&2; fail "the headless example failed"; }
cat "$work/headless.txt"
[ -s "$work/sunset.png" ] || fail "the headless example wrote no PNG"
grep -q "^wrote .*sunset.png (320x180, " "$work/headless.txt" || fail "the headless example's output"
(cd "$work" && "$work/headless/headless" "$work/x.png" /nonexistent.yaml) >"$work/bad.txt" 2>&1 &&
  fail "the headless example took a missing scene"
grep -q "nonexistent.yaml" "$work/bad.txt" || fail "the headless example's error does not name the file"
# The Vulkan host example (examples/vulkan_host): its boxes, the sky drawn around them in its
# own images and command buffer; it checks what it sees, and fails on a validation message.
run "$cmake" -S "$source/examples/vulkan_host" -B "$work/vulkan_host" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_BUILD_TYPE=Release
run "$cmake" --build "$work/vulkan_host"
(cd "$work" && "$work/vulkan_host/vulkan_host" --validate --size 160x90 "$work/host.png") \
  >"$work/vulkan_host.txt" 2>&1 || { cat "$work/vulkan_host.txt" >&2; fail "the Vulkan host example failed"; }
cat "$work/vulkan_host.txt"
[ -s "$work/host.png" ] || fail "the Vulkan host example wrote no PNG"

module=$(find "$prefix" -path '*dist-packages/skylayers*.so')
[ -n "$module" ] || fail "the install lacks the Python module"
(cd "$work" && PYTHONPATH=$(dirname "$module") "$python" -c '
import skylayers
frame = skylayers.Sky(None).render(width=8, height=4)
print("python", skylayers.data_directory(), frame["beauty"].shape)
') >"$work/python.txt" 2>&1 || { cat "$work/python.txt" >&2; fail "the installed Python module"; }
grep -qx "python $prefix/share/skylayers (4, 8, 4)" "$work/python.txt" ||
  { cat "$work/python.txt" >&2; fail "the installed Python module's frame or data"; }
echo "package_test: ok"
