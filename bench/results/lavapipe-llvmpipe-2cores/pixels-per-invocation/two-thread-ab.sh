#!/usr/bin/env bash
# usage: [LPT=2] two-thread-ab.sh ROUNDS "SCENE ARGS" -- LABEL=BIN[:KERNEL_DIR] ...
# Kernel time (gpu_ms) of the specs, interleaved render by render, LPT lavapipe threads (default 1);
# median and minimum and their ratios to the first spec, and the ray counts (which must agree).
# KERNEL_DIR: VKRAY_KERNEL_DIR, kernels compiled into a folder (docs/architecture.md).
rounds=$1; scene=$2; shift 3
for r in $(seq $rounds); do for spec in "$@"; do
  label=${spec%%=*}; rest=${spec#*=}; bin=${rest%%:*}; kd=""; [[ $rest == *:* ]] && kd=${rest#*:}
  VKRAY_KERNEL_DIR=$kd LP_NUM_THREADS=${LPT:-1} $bin render $scene -o ${TMPDIR:-/tmp}/two-thread-ab.png --json 2>/dev/null | python3 -c "import json,sys; j=json.load(sys.stdin); g=j['gpu']; print('$label', g['gpu_ms'], j['total_ms'], g['rays'], g['shadow_rays'])"
done; done > ${TMPDIR:-/tmp}/two-thread-ab.out
python3 - <<'PY'
import collections, os, statistics
d = collections.defaultdict(list)
for l in open(os.environ.get('TMPDIR', '/tmp') + '/two-thread-ab.out'):
    k, g, t, *rays = l.split(); d[k].append((float(g), float(t), ' '.join(rays)))
base = None
for k, v in d.items():
    g = statistics.median(x[0] for x in v); mn = min(x[0] for x in v); t = statistics.median(x[1] for x in v)
    if base is None: base = (g, mn)
    print(f"{k:8s} gpu_ms med {g:7.1f} min {mn:7.1f}  ratio {g/base[0]:.3f}/{mn/base[1]:.3f}  total {t:7.1f}  rays {set(x[2] for x in v)}")
PY
