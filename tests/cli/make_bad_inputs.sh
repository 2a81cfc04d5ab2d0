#!/usr/bin/env bash
# Writes the bad inputs of cli_tests.cmake that are too large or too binary to commit: UTF-16 files,
# 10 MB lines, binary garbage, a 2000-corner polygon, 2000 nested pushTransforms. Deterministic.
# usage: make_bad_inputs.sh OUTDIR VKRAY_BINARY
set -euo pipefail
out=$1
vkray=$(realpath "$2")
mkdir -p "$out"
cd "$out"

camera='camera 0 0 3 0 0 0 0 1 0 45'
triangle=$'vertex -1 -1 0\nvertex 1 -1 0\nvertex 0 1 0\ntri 0 1 2'
scene() {  # scene NAME LINES...: a scene with a camera and the given lines
  local name=$1; shift
  { echo "$camera"; printf '%s\n' "$@"; } >"$name"
}
ones() { head -c "$1" /dev/zero | tr '\0' '1'; }

# UTF-16, little-endian with a byte-order mark, and without one in both byte orders.
scene plain.scene "$triangle"
{ printf '\xff\xfe'; iconv -f UTF-8 -t UTF-16LE plain.scene; } >utf16le_bom.scene
iconv -f UTF-8 -t UTF-16LE plain.scene >utf16le.scene
iconv -f UTF-8 -t UTF-16BE plain.scene >utf16be.scene
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' | iconv -f UTF-8 -t UTF-16LE >utf16.obj
scene utf16_obj.scene "geo utf16.obj"

# 10 MB on one line: a scene line, and an OBJ number (the message quotes only its start).
{ echo "$camera"; printf 'vertex 0 0 '; ones 10000000; echo; } >long_line.scene
{ printf 'v 0 0 0\nv 1 0 0\nv 0 1 '; ones 10000000; printf '\nf 1 2 3\n'; } >long_number.obj
scene long_number_obj.scene "geo long_number.obj"

# Binary garbage as an OBJ (the vkray executable itself; as a scene it is passed directly).
cp "$vkray" garbage.obj
scene garbage_obj.scene "geo garbage.obj"

# A polygon of 2000 corners: tinyobjloader's ear clipping is quadratic or worse in the corners.
{
  for i in $(seq 0 1999); do echo "v $i $(( (i % 2) * 3 )) 0"; done
  printf 'f'; seq -s ' ' 1 2000 | sed 's/^/ /'
} >big_polygon.obj
scene big_polygon.scene "geo big_polygon.obj"

# pushTransform without popTransform, 2000 deep.
{ echo "$camera"; for _ in $(seq 2000); do echo pushTransform; done; echo "$triangle"; } >push_depth.scene
