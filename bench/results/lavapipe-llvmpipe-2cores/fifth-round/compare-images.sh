#!/usr/bin/env bash
# Identical-image check of two vkray binaries for the kd traversals: for every scene given (default:
# scenes/*.scene and scenes/stress/*.scene), renders with each binary (image and the depth, primid
# and normal AOVs as PFM) and compares the files byte for byte. Unlike ../glsl-merge/compare.sh it
# does not compare the traversal counters: this round's changes lower them on purpose.
# usage: compare-images.sh OLD_VKRAY NEW_VKRAY [SCENE...]   (from the repository root; one line per case)
set -uo pipefail
old=$1 new=$2
shift 2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(scenes/*.scene scenes/stress/*.scene)
fail=0
for s in "${scenes[@]}"; do
  size=()
  case $s in scenes/stress/*) ;; scenes/*.scene) size=(--size 160x120) ;; esac
  for a in kd-stack kd-restart kd-backtrack; do
    rm -f "$tmp"/*
    refused=0
    for v in old new; do
      bin=${!v}
      "$bin" render "$s" --accel "$a" "${size[@]}" -o "$tmp/$v.pfm" --aov "depth=$tmp/$v-depth.pfm" \
        --aov "primid=$tmp/$v-primid.pfm" --aov "normal=$tmp/$v-normal.pfm" >/dev/null 2>"$tmp/$v.err" ||
        refused=$((refused + 1))
    done
    if [ $refused -eq 2 ] && cmp -s "$tmp/old.err" "$tmp/new.err"; then
      echo "$s $a: refused by both: $(cat "$tmp/new.err")"
      continue
    fi
    result=same
    for f in "" -depth -primid -normal; do
      cmp -s "$tmp/old$f.pfm" "$tmp/new$f.pfm" || { result="DIFFERENT${f:-image}"; fail=1; }
    done
    echo "$s $a: $result"
  done
done
exit $fail
