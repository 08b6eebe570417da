#!/usr/bin/env bash
# A stand-in for `skyrender dataset` and `skyrender merge` with the same interface, for the
# self-check of tests/cluster/slurm_dataset_test.sh without a GPU or a build:
#   mock_skyrender.sh dataset SPEC --out DIR [--shard I/N]
#   mock_skyrender.sh merge DIR...
# SPEC is a fake spec with a line `count: K` (samples 0..K-1). Sample i belongs to shard
# (i mod N) + 1. Each sample takes MOCK_SAMPLE_SECONDS (default 0.5) and gives
# sample_NNNNNN.{exr,png,yaml}, whose bytes depend on the index only; each file is written to
# DIR/.tmp-NAME and renamed, then the sample's line is appended to the manifest. A rerun skips
# the samples already in the manifest.
# MOCK_SKYRENDER_BREAK (a comma-separated list) breaks it on purpose, to prove that the test
# catches it:
#   drop     shard runs leave out sample 5 (and exit 0)
#   corrupt  shard runs write different bytes for sample 3
#   tmp      shard runs leave a .tmp- file behind
#   noresume runs render again the samples already in the manifest
#   dup      merge writes sample 0 twice
#   silent   merge reports nothing and exits 0 whatever it finds
set -euo pipefail

die() { echo "error: mock_skyrender: $*" >&2; exit 1; }
broken() { case ",${MOCK_SKYRENDER_BREAK:-}," in *",$1,"*) return 0 ;; *) return 1 ;; esac; }

sha() { sha256sum "$1" | cut -d' ' -f1; }

dataset() {
  local spec="" out="" shard="" i n
  [ $# -ge 1 ] || die "dataset: missing SPEC"
  spec=$1; shift
  while [ $# -gt 0 ]; do
    case "$1" in
      --out) out=${2:?}; shift 2 ;;
      --shard) shard=${2:?}; shift 2 ;;
      *) die "dataset: unknown argument '$1'" ;;
    esac
  done
  [ -f "$spec" ] || die "dataset: cannot read spec '$spec'"
  [ -n "$out" ] || die "dataset: --out DIR is required"
  local count
  count=$(sed -n 's/^count:[[:space:]]*\([0-9][0-9]*\)[[:space:]]*$/\1/p' "$spec" | head -n1)
  [ -n "$count" ] || die "dataset: spec '$spec' has no 'count: K' line"
  local manifest
  if [ -n "$shard" ]; then
    [[ "$shard" =~ ^([0-9]+)/([0-9]+)$ ]] || die "dataset: --shard must be I/N, got '$shard'"
    i=${BASH_REMATCH[1]}; n=${BASH_REMATCH[2]}
    { [ "$n" -ge 1 ] && [ "$i" -ge 1 ] && [ "$i" -le "$n" ]; } || die "dataset: bad shard '$shard'"
    manifest="$out/manifest.$i-of-$n.jsonl"
  else
    i=1; n=1; manifest="$out/manifest.jsonl"
  fi
  mkdir -p "$out"
  local tmp=""
  trap 'rm -f "$tmp"; exit 130' INT
  trap 'rm -f "$tmp"; exit 143' TERM

  local done_list=" "
  [ -f "$manifest" ] && ! broken noresume && done_list=" $(sed -n 's/.*"index": *\([0-9][0-9]*\).*/\1/p' "$manifest" | tr '\n' ' ')"
  local k name ext line files sep
  for ((k = i - 1; k < count; k += n)); do
    case "$done_list" in *" $k "*) continue ;; esac
    if [ -n "$shard" ] && broken drop && [ $k -eq 5 ]; then continue; fi
    sleep "${MOCK_SAMPLE_SECONDS:-0.5}"
    name=$(printf 'sample_%06d' "$k")
    files=""; sep=""
    for ext in exr png yaml; do
      tmp="$out/.tmp-$name.$ext"
      {
        printf 'mock %s sample %d\n' "$ext" "$k"
        if [ -n "$shard" ] && broken corrupt && [ $k -eq 3 ]; then echo corrupted; fi
        # A little bulk, deterministic per index.
        head -c 4096 </dev/zero | tr '\0' "$(printf '\\%03o' $((65 + k % 26)))"
      } >"$tmp"
      if [ -n "$shard" ] && broken tmp && [ $k -eq 1 ]; then
        cp "$tmp" "$out/.tmp-leftover-$name.$ext"
      fi
      mv -f "$tmp" "$out/$name.$ext"
      tmp=""
      case "$ext" in yaml) key=scene ;; *) key=$ext ;; esac
      files+="$sep\"$key\": {\"name\": \"$name.$ext\", \"sha256\": \"$(sha "$out/$name.$ext")\"}"
      sep=", "
    done
    line="{\"index\": $k, \"files\": {$files}}"
    printf '%s\n' "$line" >>"$manifest"
  done
}

merge() {
  [ $# -ge 1 ] || die "merge: missing DIR"
  local out=$1 d
  local -a parts=()
  for d in "$@"; do
    [ -d "$d" ] || die "merge: '$d' is not a folder"
    for f in "$d"/manifest.*-of-*.jsonl; do [ -e "$f" ] && parts+=("$f"); done
  done
  [ ${#parts[@]} -gt 0 ] || die "merge: no manifest.I-of-N.jsonl in $*"
  python3 - "$out/manifest.jsonl" "${MOCK_SKYRENDER_BREAK:-}" "${parts[@]}" <<'EOF'
import json, os, re, sys
dest, brk, parts = sys.argv[1], sys.argv[2].split(","), sys.argv[3:]
lines, shards = {}, {}
bad = []
for p in parts:
    m = re.search(r'manifest\.(\d+)-of-(\d+)\.jsonl$', p)
    shards.setdefault(int(m.group(2)), set()).add(int(m.group(1)))
    for l in open(p):
        if l.strip():
            o = json.loads(l)
            lines.setdefault(o["index"], []).append(l.rstrip("\n"))
for n, got in shards.items():
    for i in sorted(set(range(1, n + 1)) - got):
        bad.append(f"shard {i}/{n}: no manifest")
for k, ls in sorted(lines.items()):
    if len(ls) > 1:
        bad.append(f"index {k}: present {len(ls)} times")
top = max(lines) if lines else -1
for k in range(top + 1):
    if k not in lines:
        bad.append(f"index {k}: missing")
tmp = dest + ".tmp-merge"
with open(tmp, "w") as f:
    for k in sorted(lines):
        f.write(lines[k][0] + "\n")
        if "dup" in brk and k == 0:
            f.write(lines[k][0] + "\n")
os.replace(tmp, dest)
if "silent" in brk:
    bad = []
for b in bad:
    print("merge: " + b, file=sys.stderr)
sys.exit(1 if bad else 0)
EOF
}

[ $# -ge 1 ] || die "usage: mock_skyrender.sh dataset|merge ..."
cmd=$1; shift
case "$cmd" in
  dataset) dataset "$@" ;;
  merge) merge "$@" ;;
  *) die "unknown command '$cmd'" ;;
esac
