#!/usr/bin/env bash
# Seed corpora and dictionaries of the fuzz targets of tests/fuzz, in DIR/NAME/ and DIR/NAME.dict for
# each target NAME (scene, obj, off, ply, gltf, image):
#   scene  every .scene of scenes/ and of the tests as it is, and every mesh seed below wrapped as
#          "geo m.EXT" + "#@ m.EXT" + the file (+ the files it names), the input format of fuzz_common.h
#   obj    the OBJ files of the tests and scenes/models, each followed by the MTL files beside it as "#@ NAME"
#   off    the OFF files of the tests;  ply  theirs and PLY files written here (ASCII, binary little- and
#   big-endian);  gltf  theirs and glTF files written here (embedded buffer, external buffer, GLB)
#   image  tests/fuzz/seeds/image: small PNG (8- and 16-bit, grey, palette), BMP, PFM and EXR files
# and, for every target, the minimised inputs of past findings in tests/fuzz/regressions/NAME/.
# usage: tests/fuzz/make_corpus.sh DIR
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
out=$1
targets=(scene obj off ply gltf image)
for t in "${targets[@]}"; do rm -rf "${out:?}/$t"; mkdir -p "$out/$t"; done

# Dictionaries: each format's words and, for the text formats, text.dict's; the scene target reaches
# every mesh format, so it gets them all.
for t in obj off ply gltf; do cat "$here/$t.dict" "$here/text.dict" >"$out/$t.dict"; done
cat "$here"/{scene,obj,off,ply,gltf,text}.dict >"$out/scene.dict"
cp "$here/image.dict" "$out/image.dict"

for f in "$root"/scenes/*.scene "$root"/scenes/*/*.scene "$root"/tests/cli/data/*.scene \
         "$root"/tests/scene/data/*.scene; do
  [[ -f $f ]] && cp "$f" "$out/scene/$(basename "$(dirname "$f")")-$(basename "$f")"
done
for f in "$root"/tests/scene/data/*.obj "$root"/tests/scene/data/*/*.obj "$root"/tests/cli/data/*.obj \
         "$root"/scenes/models/*.obj; do
  [[ -f $f ]] || continue
  {
    # The OBJ's mtllib names stay as they are; its MTL files come along under those names.
    cat "$f"
    for m in "$(dirname "$f")"/*.mtl; do
      [[ -f $m ]] && { printf '\n#@ %s\n' "$(basename "$m")"; cat "$m"; }
    done
  } >"$out/obj/$(basename "$(dirname "$f")")-$(basename "$f")"
done
for f in "$root"/tests/scene/data/*.off "$root"/tests/cli/data/*.off; do
  [[ -f $f ]] && cp "$f" "$out/off/$(basename "$(dirname "$f")")-$(basename "$f")"
done
for f in "$root"/tests/cli/data/*.ply; do [[ -f $f ]] && cp "$f" "$out/ply/"; done
for f in "$root"/tests/cli/data/*.gltf; do [[ -f $f ]] && cp "$f" "$out/gltf/"; done
cp "$here"/seeds/image/* "$out/image/"

ply_head() {  # FORMAT [extra vertex properties]
  printf 'ply\nformat %s 1.0\ncomment vkray seed\nelement vertex 4\nproperty float x\nproperty float y\n' "$1"
  printf 'property float z\n%belement face 2\nproperty list uchar int vertex_indices\nend_header\n' "${2:-}"
}
{ ply_head ascii 'property uchar red\nproperty uchar green\nproperty uchar blue\n'
  printf '0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 9 9 9\n4 0 1 2 3\n3 3 1 0\n'; } >"$out/ply/ascii.ply"
# The unit square's corners as floats (0 = 00000000, 1 = 3f800000), then a quad and a triangle.
{ ply_head binary_little_endian
  printf '\0\0\0\0\0\0\0\0\0\0\0\0\0\0\x80\x3f\0\0\0\0\0\0\0\0\0\0\x80\x3f\0\0\x80\x3f\0\0\0\0'
  printf '\0\0\0\0\0\0\x80\x3f\0\0\0\0'
  printf '\x04\0\0\0\0\x01\0\0\0\x02\0\0\0\x03\0\0\0\x03\x03\0\0\0\x01\0\0\0\0\0\0\0'; } >"$out/ply/le.ply"
{ ply_head binary_big_endian 'property float nx\nproperty float ny\nproperty float nz\n'
  for v in '\0\0\0\0\0\0\0\0' '\x3f\x80\0\0\0\0\0\0' '\x3f\x80\0\0\x3f\x80\0\0' '\0\0\0\0\x3f\x80\0\0'; do
    printf "$v"'\0\0\0\0\0\0\0\0\0\0\0\0\x3f\x80\0\0'
  done
  printf '\x04\0\0\0\0\0\0\0\x01\0\0\0\x02\0\0\0\x03\x03\0\0\0\x03\0\0\0\x01\0\0\0\0'; } >"$out/ply/be.ply"
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
gltf_json ", \"uri\": \"data:application/octet-stream;base64,$tri_b64\"" >"$out/gltf/embedded.gltf"
{ gltf_json ', "uri": "m.bin"'; printf '#@ m.bin\n'; printf '%s' "$tri_b64" | base64 -d; } >"$out/gltf/external.gltf"
# GLB: 12-byte header, the JSON chunk padded with spaces to 4 bytes, the 36-byte BIN chunk.
json=$(gltf_json '')
while (( ${#json} % 4 )); do json+=' '; done
le32() { printf "\\x$(printf %02x $(($1 & 255)))\\x$(printf %02x $(($1 >> 8 & 255)))\\x$(printf %02x $(($1 >> 16 & 255)))\\x$(printf %02x $(($1 >> 24 & 255)))"; }
{ printf 'glTF'; le32 2; le32 $((12 + 8 + ${#json} + 8 + 36)); le32 ${#json}; printf 'JSON%s' "$json"
  le32 36; printf 'BIN\0'; printf '%s' "$tri_b64" | base64 -d; } >"$out/gltf/binary.glb"

# The scene target loads each mesh seed through a `geo` line. A GLB is taken whole by fuzz_common.h's
# splitting too: its bytes hold no "#@ " line start.
for t in obj off ply gltf; do
  for f in "$out/$t"/*; do
    ext=${f##*.}
    { printf 'camera 0 0 5 0 0 0 0 1 0 45\ngeo m.%s\n#@ m.%s\n' "$ext" "$ext"; cat "$f"; } \
      >"$out/scene/mesh-$(basename "$f")"
  done
done
for t in "${targets[@]}"; do
  [[ -d $here/regressions/$t ]] && cp "$here/regressions/$t"/* "$out/$t/" 2>/dev/null || true
done
summary=""
for t in "${targets[@]}"; do summary+=" $t $(find "$out/$t" -type f | wc -l),"; done
echo "make_corpus: seeds in $out:${summary%,}"
