#!/usr/bin/env bash
# usage: measure.sh OLD_VKRAY NEW_VKRAY OUTDIR — every figure of docs/benchmarks.md, "What a small
# render pays before and after its kernels", from the repository root: Vulkan's start, pipeline
# creation per kernel against a trivial kernel's, the dropped single trace call and the five-fetch
# bound, the AAC tree against the binned-SAH one, and the whole command before and after this round.
set -euo pipefail
old=$1; new=$2; out=$3; here=$(dirname "$0"); mkdir -p "$out"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
med() { python3 -c 'import sys, statistics as s; v = [float(x) for x in sys.stdin.read().split()]; print("median %.1f min %.1f n %d" % (s.median(v), min(v), len(v)))'; }

{ echo "# vkray devices, whole command (ms): the Vulkan loader, every installed driver, lavapipe's device"
  for i in $(seq 9); do s=$(date +%s%N); $new devices > /dev/null; e=$(date +%s%N); echo $(( (e - s) / 1000 )); done |
    awk '{print $1 / 1000}' | med
} > "$out/vulkan-start.txt"

# Pipeline creation (ms) on scenes/objects.scene: the kernels, and a trivial one in brute's place.
mkdir -p "$tmp/trivial"
glslangValidator --target-env vulkan1.1 -Os --quiet -o "$tmp/trivial/render_brute.spv" "$here/trivial.comp"
{ for a in trivial brute bvh kd-stack kd-restart kd-backtrack; do
    kd=""; acc=$a; [[ $a == trivial ]] && kd=$tmp/trivial && acc=brute
    VKRAY_KERNEL_DIR=$kd $new render scenes/objects.scene --accel $acc -o "$tmp/p.png" --quiet 2>/dev/null  # warm
    echo "$a pipeline_ms $(for i in $(seq 7); do VKRAY_KERNEL_DIR=$kd $new render scenes/objects.scene --accel $acc -o "$tmp/p.png" --json 2>/dev/null |
      python3 -c 'import json, sys; print(json.load(sys.stdin)["gpu"]["pipeline_ms"])'; done | med)"
  done
} > "$out/pipeline-per-kernel.txt"

# The single trace call (dropped): the kernels of this tree with dropped/one-trace-call.diff applied.
git archive HEAD shaders | tar -x -C "$tmp"
bash "$here/compile-kernels.sh" "$tmp/shaders" "$tmp/base"
(cd "$tmp" && patch -s -p1 < "$OLDPWD/$here/dropped/one-trace-call.diff")
bash "$here/compile-kernels.sh" "$tmp/shaders" "$tmp/one-call"
ab=bench/results/lavapipe-llvmpipe-2cores/node-steps/kernel-ab.sh
for s in objects cornell; do
  for k in base one-call; do VKRAY_KERNEL_DIR=$tmp/$k $new render scenes/$s.scene -o "$tmp/w.png" --quiet 2>/dev/null; done
  echo "## $s: kernel time, one lavapipe thread"; LP_NUM_THREADS=1 bash $ab 5 scenes/$s.scene -- $new:$tmp/base $new:$tmp/one-call
  echo "## $s: pipeline creation"; METRIC='d["gpu"]["pipeline_ms"]' bash $ab 5 scenes/$s.scene -- $new:$tmp/base $new:$tmp/one-call
done > "$out/one-trace-call.txt" 2>&1

# A fifth texel fetch a node step (the child texel again, at an index the compiler cannot prove equal).
rm -rf "$tmp/shaders"; git archive HEAD shaders | tar -x -C "$tmp"
sed -i 's/nodeTexel(k + 3));$/nodeTexel(k + 3) \& nodeTexel(k + 3 + int(index >> 31u)));/' "$tmp/shaders/include/bvh_common.glsl"
grep -q 'index >> 31u' "$tmp/shaders/include/bvh_common.glsl"
bash "$here/compile-kernels.sh" "$tmp/shaders" "$tmp/five"
for k in base five; do VKRAY_KERNEL_DIR=$tmp/$k $new render scenes/primary/bunny.scene --view close --size 512x384 -o "$tmp/w.png" --quiet 2>/dev/null; done
LP_NUM_THREADS=1 bash $ab 9 scenes/primary/bunny.scene --view close --size 512x384 -- $new:$tmp/base $new:$tmp/five > "$out/five-fetches.txt" 2>&1

# The AAC tree (bvh) against the binned-SAH one (bvh-sah): counters and kernel time, camera rays.
for m in bunny armadillo dragon; do
  for a in bvh bvh-sah; do
    $new render scenes/primary/$m.scene --view close --size 512x384 --accel $a --counters --json -o "$tmp/c.png" 2>/dev/null |
      python3 -c "import json, sys; d = json.load(sys.stdin); t = d['gpu']['traversal']; n = 512 * 384
print('$m $a: build %.0f ms, sah_cost %.2f, node steps %.2f, triangle tests %.2f a ray' % (d['accel']['build_ms'], d['accel']['sah_cost'], t['nodes'] / n, t['triangles'] / n))"
  done
  VKRAY=$new LP_NUM_THREADS=1 bash "$here/accel-ab.sh" 7 scenes/primary/$m.scene --view close --size 512x384 -- bvh bvh-sah
done > "$out/aac-against-sah.txt" 2>&1

# The whole command, the binary before this round against this one.
for s in objects elephant cornell; do
  echo "## $s, GPU"; bash "$here/whole-command-ab.sh" 9 scenes/$s.scene $old $new
  echo "## $s, --cpu"; bash "$here/whole-command-ab.sh" 9 scenes/$s.scene $old $new --cpu
done > "$out/whole-command.txt" 2>&1
for b in $old $new; do /usr/bin/time -f "$b: %e s, peak RSS %M KB" $b render scenes/cornell.scene --size 3840x2160 -o "$tmp/big.png" --quiet; done 2> "$out/cornell-3840x2160.txt"
