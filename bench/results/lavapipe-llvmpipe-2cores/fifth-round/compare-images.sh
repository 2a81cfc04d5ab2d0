#!/usr/bin/env bash
# Identical-image check of two vkray binaries for the kd traversals (image, depth, primid and normal
# AOVs, byte for byte), on every scene given (default: scenes/*.scene and scenes/stress/*.scene):
# ../glsl-merge/compare.sh without its counters, which this round's changes lower on purpose.
# usage: compare-images.sh OLD_VKRAY NEW_VKRAY [SCENE...]   (from the repository root; one line per case)
here=$(dirname "$0")
[ $# -gt 2 ] || set -- "$1" "$2" scenes/*.scene scenes/stress/*.scene
ACCELS="kd-stack kd-restart kd-backtrack" COUNTERS=no exec bash "$here/../glsl-merge/compare.sh" "$@"
