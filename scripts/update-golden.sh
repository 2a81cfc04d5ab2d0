#!/usr/bin/env bash
# Regenerates the golden images tests/golden/NAME.png deliberately: renders every hand-made scene
# of scenes/ (those without a fetched `geo meshes/...` mesh) with the GPU path on lavapipe at
# 160x120, exactly as tests/golden/golden_tests.cmake does, and prints how each new image differs
# from the one it replaces. Nothing runs this automatically, least of all a failing test: look at
# the new images before committing them, with the change that explains them.
#
# usage: scripts/update-golden.sh [-B BUILD_DIR] [SCENE_NAME...]     (default: build, all scenes)
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$root/build"
if [[ "${1:-}" == "-B" ]]; then
  [[ $# -ge 2 ]] || { echo "update-golden: -B needs a build directory" >&2; exit 1; }
  build=$(cd "$2" && pwd); shift 2
fi
vkray="$build/vkray"
[[ -x "$vkray" ]] || { echo "update-golden: $vkray not found; build first (make build) or pass -B DIR" >&2; exit 1; }

size=160x120    # keep in step with GOLDEN_SIZE and GOLDEN_DEVICE in tests/golden/golden_tests.cmake
device=llvmpipe
golden="$root/tests/golden"
mkdir -p "$golden"

names=("$@")
if [[ ${#names[@]} -eq 0 ]]; then
  for scene in "$root"/scenes/*.scene; do
    grep -Eq '^(geo|obj)[[:space:]]+meshes/' "$scene" && continue  # fetched meshes: no golden
    names+=("$(basename "$scene" .scene)")
  done
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for name in "${names[@]}"; do
  scene="$root/scenes/$name.scene"
  [[ -f "$scene" ]] || { echo "update-golden: no scene $scene" >&2; exit 1; }
  "$vkray" render "$scene" --size "$size" --device "$device" -o "$tmp/$name.png" >/dev/null
  if [[ -f "$golden/$name.png" ]]; then
    if "$vkray" compare "$golden/$name.png" "$tmp/$name.png" --threshold 0 --max-bad-fraction 0 >/dev/null; then
      echo "update-golden: $name.png unchanged"
      continue
    fi
    echo "update-golden: $name.png changed:"
    "$vkray" compare "$golden/$name.png" "$tmp/$name.png" | sed -n 's/^  /    /p' | grep -E 'RMSE|bad pixels'
  else
    echo "update-golden: $name.png new"
  fi
  cp "$tmp/$name.png" "$golden/$name.png"
done
echo "update-golden: done; review with git diff --stat tests/golden/ and look at the images before committing"
