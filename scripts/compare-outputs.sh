#!/usr/bin/env bash
# Identical-output check of two vkray binaries (docs/performance.md, "Tools"), which a change meant
# only to be faster must pass. For every scene and accelerator, renders with each
# (image and the depth, primid and normal AOVs as PFM) and compares the files byte for byte; then
# renders again with --counters and compares the JSON report's ray and traversal counters (not the
# list of compiled-in features, which names what each binary can leave out).
# A scene both binaries refuse (stress/empty.scene: no triangles) is reported as "refused by both".
# ACCELS="kd-stack kd-restart" narrows the accelerators; COUNTERS=no skips the counters (for
# changes that lower them on purpose).
# usage: [ACCELS=...] [COUNTERS=no] scripts/compare-outputs.sh OLD_VKRAY NEW_VKRAY [SCENE...]   (repository root)
#   default scenes: scenes/default.scene, scenes/cornell.scene and every scenes/stress/*.scene
set -uo pipefail
[ $# -ge 2 ] || { awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0" >&2; exit 2; }
old=$1 new=$2
shift 2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
read -r -a accels <<< "${ACCELS:-brute bvh bvh-fast kd-stack kd-restart kd-backtrack}"
withCounters=${COUNTERS:-yes}
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(scenes/default.scene scenes/cornell.scene scenes/stress/*.scene)
counters() {  # the report's gpu counters, without timings
  python3 -c 'import json,sys; g=json.load(sys.stdin)["gpu"]; print(json.dumps({k:v for k,v in g.items() if not k.endswith("_ms") and k != "features"}, sort_keys=True))'
}
fail=0
for s in "${scenes[@]}"; do
  size=()
  case $s in scenes/stress/*) ;; scenes/*.scene) size=(--size 160x120) ;; esac
  for a in "${accels[@]}"; do
    rm -f "$tmp"/*
    refused=0
    for v in old new; do
      bin=${!v}
      if ! "$bin" render "$s" --accel "$a" "${size[@]}" -o "$tmp/$v.pfm" --aov "depth=$tmp/$v-depth.pfm" \
        --aov "primid=$tmp/$v-primid.pfm" --aov "normal=$tmp/$v-normal.pfm" >/dev/null 2>"$tmp/$v.err"; then
        refused=$((refused + 1))
        continue
      fi
      [ "$withCounters" = no ] && continue
      "$bin" render "$s" --accel "$a" "${size[@]}" -o "$tmp/$v-c.pfm" --counters --json 2>/dev/null | counters >"$tmp/$v.counters"
    done
    if [ $refused -eq 2 ] && cmp -s "$tmp/old.err" "$tmp/new.err"; then
      echo "$s $a: refused by both: $(cat "$tmp/new.err")"
      continue
    fi
    result=same
    for f in "" -depth -primid -normal; do
      cmp -s "$tmp/old$f.pfm" "$tmp/new$f.pfm" || { result="DIFFERENT${f:-image}"; fail=1; }
    done
    if [ "$withCounters" = no ]; then
      echo "$s $a: $result"
      continue
    fi
    cmp -s "$tmp/old.counters" "$tmp/new.counters" || { result="$result counters-DIFFERENT"; fail=1; diff "$tmp/old.counters" "$tmp/new.counters"; }
    echo "$s $a: $result $(cat "$tmp/new.counters")"
  done
done
exit $fail
