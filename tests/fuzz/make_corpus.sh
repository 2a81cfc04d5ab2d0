#!/usr/bin/env bash
# Seed corpus of vkray_fuzz_scene_parser in DIR: every .scene of scenes/ and of the tests, as it is,
# and every OBJ and OFF file of the tests wrapped as "geo m.obj" + "#@ m.obj" + the file (+ the MTL
# files beside it as "#@ NAME"), the multi-file input format of scene_parser_fuzz.cpp.
# usage: tests/fuzz/make_corpus.sh DIR
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=$1
mkdir -p "$out"
n=0
for f in "$root"/scenes/*.scene "$root"/scenes/*/*.scene "$root"/tests/cli/data/*.scene \
         "$root"/tests/scene/data/*.scene; do
  [[ -f $f ]] || continue
  cp "$f" "$out/scene-$(basename "$(dirname "$f")")-$(basename "$f")"
  n=$((n + 1))
done
for f in "$root"/tests/scene/data/*.obj "$root"/tests/scene/data/*/*.obj "$root"/tests/cli/data/*.obj \
         "$root"/scenes/models/*.obj "$root"/tests/cli/data/*.off; do
  [[ -f $f ]] || continue
  ext=${f##*.}
  {
    printf 'camera 0 0 5 0 0 0 0 1 0 45\ngeo m.%s\n#@ m.%s\n' "$ext" "$ext"
    # The OBJ's mtllib names stay as they are; its MTL files come along under those names.
    cat "$f"
    for m in "$(dirname "$f")"/*.mtl; do
      [[ -f $m ]] && { printf '\n#@ %s\n' "$(basename "$m")"; cat "$m"; }
    done
  } >"$out/mesh-$(basename "$(dirname "$f")")-$(basename "$f")"
  n=$((n + 1))
done
echo "make_corpus: $n seeds in $out"
