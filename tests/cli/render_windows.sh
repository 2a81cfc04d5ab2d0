#!/usr/bin/env bash
# `vkray render`'s windows end to end on the GPU (lavapipe without one): four --tile renders joined by
# `vkray assemble` are bit-identical to the whole render (EXR floats; colour with reflections and
# two samples a pixel), so is a --crop window's EXR placed by its data window (its four numbers
# comma-separated or four arguments), --pixel prints the
# pixel of the whole render, and several scenes in one call land in --out-dir under their own names;
# on the GPU a scene that needs an earlier scene's kernel pipeline renders with it, bit-identical to
# its render alone (the pipeline's descriptors then name the second scene's buffers).
# usage: render_windows.sh VKRAY SCENE_DIR OUT_DIR
set -euo pipefail
vkray=$1 scenes=$2 out=$3/windows
rm -rf "$out" && mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
scene=$scenes/default.scene
args=(--size 96x72 --spp 2 --accel bvh)

"$vkray" render "$scene" "${args[@]}" --quiet -o "$out/full.exr"
"$vkray" render "$scene" "${args[@]}" --quiet --save-accel "$out/s.vkacc" --build-only
[[ -s "$out/s.vkacc" ]] || fail "--build-only wrote no structure file"
for i in 0 1 2 3; do
  "$vkray" render "$scene" "${args[@]}" --quiet --load-accel "$out/s.vkacc" --tile $i/4 -o "$out/tile-$i.exr"
done
"$vkray" assemble "$out"/tile-{3,1,0,2}.exr -o "$out/assembled.exr"
"$vkray" compare "$out/full.exr" "$out/assembled.exr" --threshold 0 --max-rmse 0 --max-bad-fraction 0 \
  || fail "the assembled tiles differ from the whole render"

# A missing tile is named, and nothing is written.
if msg=$("$vkray" assemble "$out"/tile-{0,1,3}.exr -o "$out/partial.exr" 2>&1); then fail "assembled 3 of 4 tiles"; fi
echo "$msg"
grep -q "missing tile.* 2 of 4" <<<"$msg" || fail "the missing tile 2 is not named"
[[ ! -e "$out/partial.exr" ]] || fail "a partial image was written"

# A crop window: the same pixels as the whole render, placed where they belong.
"$vkray" render "$scene" "${args[@]}" --quiet --crop 0.25,0.75,0.5,1 -o "$out/crop.exr"
"$vkray" assemble "$out/crop.exr" -o "$out/crop-alone.exr" 2>/dev/null && fail "a crop window assembled into a whole image"
"$vkray" convert "$out/crop.exr" "$out/crop.pfm" >/dev/null
"$vkray" render "$scene" "${args[@]}" --quiet --pixel-bounds 24,72,36,72 -o "$out/bounds.pfm"
"$vkray" compare "$out/crop.pfm" "$out/bounds.pfm" --threshold 0 --max-rmse 0 --max-bad-fraction 0 \
  || fail "--crop 0.25,0.75,0.5,1 and --pixel-bounds 24,72,36,72 differ"
# pbrt-v3's form, four arguments (before the scene, which stays a scene), and the same for the bounds.
"$vkray" render --crop 0.25 0.75 0.5 1 "$scene" "${args[@]}" --quiet -o "$out/crop4.exr"
cmp "$out/crop.exr" "$out/crop4.exr" || fail "--crop 0.25 0.75 0.5 1 and --crop 0.25,0.75,0.5,1 differ"
"$vkray" render --pixel-bounds 24 72 36 72 "$scene" "${args[@]}" --quiet -o "$out/bounds4.pfm"
cmp "$out/bounds.pfm" "$out/bounds4.pfm" || fail "--pixel-bounds 24 72 36 72 and 24,72,36,72 differ"

# --pixel prints the pixel (its values are the whole render's: tests/gpu, tests/cpu).
line=$("$vkray" render "$scene" "${args[@]}" --pixel 40,30)
echo "$line"
grep -Eq "^pixel 40,30 of 96x72: colour [0-9.e+-]+ [0-9.e+-]+ [0-9.e+-]+, depth [0-9.]+, triangle [0-9]+, normal" <<<"$line" \
  || fail "--pixel printed no pixel line"
grep -q "^  camera ray, depth 1: origin" <<<"$line" || fail "--pixel printed no trace of the camera ray"
grep -Eq "^  radiance [0-9.e+-]+ " <<<"$line" || fail "--pixel printed no traced radiance"

# Several scenes in one call, each under its own name in --out-dir.
mkdir -p "$out/many"
"$vkray" render "$scenes/default.scene" "$scenes/cornell.scene" --cpu --size 32x24 --quiet --out-dir "$out/many"
[[ -s "$out/many/default.png" && -s "$out/many/cornell.png" ]] || fail "--out-dir holds $(ls "$out/many")"

# Two scenes of the same kernel features (at one maxdepth) on the GPU: the second creates no pipeline
# and renders as it does alone.
many=(--size 48x36 --maxdepth 4 --accel bvh)
mkdir -p "$out/gpu-many"
"$vkray" render "$scenes/default.scene" "$scenes/cornell.scene" "${many[@]}" --json --out-dir "$out/gpu-many" > "$out/gpu-many.json"
created=$(jq -r '[.[].gpu.pipelines_created | tostring] | join(" ")' "$out/gpu-many.json")
[[ $created == "1 0" ]] || fail "pipelines created by the two scenes: $created (expected 1 0)"
for s in default cornell; do
  "$vkray" render "$scenes/$s.scene" "${many[@]}" --quiet -o "$out/gpu-alone-$s.png"
  "$vkray" compare "$out/gpu-many/$s.png" "$out/gpu-alone-$s.png" --threshold 0 --max-rmse 0 --max-bad-fraction 0 \
    || fail "$s.scene rendered after another scene differs from its render alone"
done
echo "ok: tiles assembled bit-identical, crop = pixel bounds, --pixel printed, two scenes in --out-dir, a pipeline shared"
