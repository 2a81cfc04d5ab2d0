#!/bin/bash
# Interleaved A/B of kd-tree build settings by GPU time (the `gpu` figure of `vkray render --stats`,
# Vulkan timestamps): camera rays only, the close-up view, ROUNDS rounds of every option set in turn,
# medians. Run from the repository root after `make build`.
#   kd-gpu-ab.sh SCENE ACCEL ROUNDS "TUNING A" "TUNING B" ...   ("" = the defaults)
# Example: kd-gpu-ab.sh scenes/primary/bunny.scene kd-stack 5 ":kd-empty-bonus=0.5" ":kd-empty-bonus=0"
scene=$1; accel=$2; rounds=$3; shift 3
declare -A res
for r in $(seq "$rounds"); do
  i=0
  for o in "$@"; do
    ms=$(build/vkray render "$scene" --accel "$accel$o" --view close --size 1024x768 --maxdepth 1 --stats \
           -o /tmp/kd-gpu-ab.png 2>&1 | grep -oE "gpu [0-9.]+ ms" | grep -oE "[0-9.]+")
    res[$i]="${res[$i]} $ms"; i=$((i + 1))
  done
done
i=0
for o in "$@"; do
  med=$(echo ${res[$i]} | tr ' ' '\n' | sort -n | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}')
  echo "[$o] median $med ms, all:${res[$i]}"; i=$((i + 1))
done
