#!/usr/bin/env bash
# Seed corpus of vkray_fuzz_scene_parser in DIR: every .scene of scenes/ and of the tests, as it is,
# and every OBJ and OFF file of the tests wrapped as "geo m.obj" + "#@ m.obj" + the file (+ the MTL
# files beside it as "#@ NAME"), the multi-file input format of scene_parser_fuzz.cpp; and PLY (ASCII,
# binary little- and big-endian) and glTF (embedded buffer, external buffer, GLB) meshes written here.
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
# A seed whose scene loads m.EXT, the mesh read from stdin.
# (Run at the end of a pipe, in a subshell: the count below is of the files.)
mesh_seed() {  # NAME EXT: the mesh on stdin
  { printf 'camera 0 0 5 0 0 0 0 1 0 45\ngeo m.%s\n#@ m.%s\n' "$2" "$2"; cat; } >"$out/mesh-$1"
}
ply_head() {  # FORMAT [extra vertex properties]
  printf 'ply\nformat %s 1.0\ncomment vkray seed\nelement vertex 4\nproperty float x\nproperty float y\n' "$1"
  printf 'property float z\n%belement face 2\nproperty list uchar int vertex_indices\nend_header\n' "${2:-}"
}
{ ply_head ascii 'property uchar red\nproperty uchar green\nproperty uchar blue\n'
  printf '0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 9 9 9\n4 0 1 2 3\n3 3 1 0\n'; } | mesh_seed ascii.ply ply
# The unit square's corners as floats (0 = 00000000, 1 = 3f800000), then a quad and a triangle.
{ ply_head binary_little_endian
  printf '\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x80\x3f\0\0\0\0\0\0\0\0\0\0\x80\x3f\0\0\x80\x3f\0\0\0\0'
  printf '\0\0\0\0\0\0\x80\x3f\0\0\0\0'
  printf '\x04\0\0\0\0\x01\0\0\0\x02\0\0\0\x03\0\0\0\x03\x03\0\0\0\x01\0\0\0\0\0\0\0'; } | mesh_seed le.ply ply
{ ply_head binary_big_endian 'property float nx\nproperty float ny\nproperty float nz\n'
  for v in '\0\0\0\0\0\0\0\0' '\x3f\x80\0\0\0\0\0\0' '\x3f\x80\0\0\x3f\x80\0\0' '\0\0\0\0\x3f\x80\0\0'; do
    printf "$v"'\0\0\0\0\0\0\0\0\0\0\0\0\x3f\x80\0\0'
  done
  printf '\x04\0\0\0\0\0\0\0\x01\0\0\0\x02\0\0\0\x03\x03\0\0\0\x03\0\0\0\x01\0\0\0\0'; } | mesh_seed be.ply ply
# glTF: one triangle (three float VEC3 positions, 36 bytes) and a two-node hierarchy with a material.
tri_b64='AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA'
gltf_json() {  # BUFFER-URI-MEMBER
  printf '{"asset": {"version": "2.0"}, "buffers": [{"byteLength": 36%s}],\n' "$1"
  printf '"bufferViews": [{"buffer": 0, "byteLength": 36}],\n'
  printf '"accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],\n'
  printf '"materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.2, 1], "metallicFactor": 0}}],\n'
  printf '"meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0, "mode": 4}]}],\n'
  printf '"nodes": [{"children": [1], "translation": [0, 1, 0]}, {"mesh": 0, "scale": [2, 2, 2]}],\n'
  printf '"scenes": [{"nodes": [0]}], "scene": 0}\n'
}
gltf_json ", \"uri\": \"data:application/octet-stream;base64,$tri_b64\"" | mesh_seed embedded.gltf gltf
{ gltf_json ', "uri": "m.bin"'; printf '#@ m.bin\n'; printf '%s' "$tri_b64" | base64 -d; } | mesh_seed external.gltf gltf
# GLB: 12-byte header, the JSON chunk padded with spaces to 4 bytes, the 36-byte BIN chunk.
json=$(gltf_json '')
while (( ${#json} % 4 )); do json+=' '; done
le32() { printf "\\x$(printf %02x $(($1 & 255)))\\x$(printf %02x $(($1 >> 8 & 255)))\\x$(printf %02x $(($1 >> 16 & 255)))\\x$(printf %02x $(($1 >> 24 & 255)))"; }
{ printf 'glTF'; le32 2; le32 $((12 + 8 + ${#json} + 8 + 36)); le32 ${#json}; printf 'JSON%s' "$json"
  le32 36; printf 'BIN\0'; printf '%s' "$tri_b64" | base64 -d; } | mesh_seed binary.glb glb
n=$((n + 6))  # the PLY and glTF seeds
echo "make_corpus: $n seeds in $out"
