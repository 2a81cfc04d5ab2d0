#!/usr/bin/env bash
# Fetches the real meshes of scenes/*.scene into scenes/meshes/ (git-ignored: they are not ours to
# commit) from two Debian packages, without installing either:
#   glmark2-data   usr/share/glmark2/models/bunny.obj                 the Stanford bunny
#   libcgal-demo   usr/share/doc/libcgal-dev/data.tar.gz, data/meshes/ the Armadillo, the Chinese
#                  dragon, the elephant (coarse and refined), the diplodocus
# Each .deb is fetched with `apt-get download` into a cache and unpacked with dpkg-deb -x there;
# every mesh copied out is checked against the sha256 below. Idempotent: when all meshes are in
# place with the right checksums, a run only verifies them (no network).
#
# usage: scripts/fetch-scenes.sh [--verify]     (--verify: check, never download; exit 1 if not ok)
# env:   VKRAY_CACHE  where the .debs and their contents go (default ~/.cache/vkray/debs)
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
dest="$root/scenes/meshes"
cache="${VKRAY_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/vkray/debs}"

# name in scenes/meshes | package | path in the package (a tarball member after '!') | sha256
meshes=(
  "bunny.obj|glmark2-data|usr/share/glmark2/models/bunny.obj|bff773d28c62e80187b2dfa8c6c8cc771a4c7707ddcdcf2e515913d322d1f548"
  "armadillo.off|libcgal-demo|usr/share/doc/libcgal-dev/data.tar.gz!data/meshes/armadillo.off|6f7f3ca1abc506569466b72f2f59d49493a284e7376d7a7e23c08115ec8cec4e"
  "ChineseDragon-10kv.off|libcgal-demo|usr/share/doc/libcgal-dev/data.tar.gz!data/meshes/ChineseDragon-10kv.off|f633bdfaac7a0f99e0fab668c34862f0c26f341cfdb4665bab282d79b788db02"
  "elephant.off|libcgal-demo|usr/share/doc/libcgal-dev/data.tar.gz!data/meshes/elephant.off|be4e1ea68f5f840a3d2ada69d828222e76a57d9e25b21e19a9deacd3f2328e02"
  "refined_elephant.off|libcgal-demo|usr/share/doc/libcgal-dev/data.tar.gz!data/meshes/refined_elephant.off|a170eed4ef33ef412a72b824d791f69ea59ee5f5a7c12dc1ae9077b6eb030650"
  "diplodocus.off|libcgal-demo|usr/share/doc/libcgal-dev/data.tar.gz!data/meshes/diplodocus.off|661fdac29eca4b205e354da112b3cbfd08dcfae07df989234b71421e62521c96"
)

die() { echo "fetch-scenes: error: $*" >&2; exit 1; }
say() { echo "fetch-scenes: $*"; }

verify_only=0
case "${1:-}" in
  "") ;;
  --verify) verify_only=1 ;;
  *) die "unknown argument '$1' (usage: scripts/fetch-scenes.sh [--verify])" ;;
esac

for tool in sha256sum apt-get dpkg-deb tar; do
  command -v "$tool" >/dev/null || die "'$tool' not found (a Debian or Ubuntu machine is needed)"
done

sha_of() { sha256sum "$1" | cut -d' ' -f1; }

# True when scenes/meshes/NAME exists with the expected checksum.
in_place() { [[ -f "$dest/$1" && "$(sha_of "$dest/$1")" == "$2" ]]; }

# apt-get update needs root; as the install script does, use sudo when not root.
apt_update() {
  local sudo=()
  if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null || die "package lists lack '$1' and updating them needs root or sudo"
    sudo=(sudo)
  fi
  say "package '$1' unknown to apt: running apt-get update"
  "${sudo[@]}" apt-get update -qq || die "apt-get update failed"
}

# Downloads and unpacks PACKAGE once into $cache/PACKAGE/ (the unpacked tree marks it done).
unpack_package() {
  local pkg=$1 dir="$cache/$1"
  [[ -f "$dir/.unpacked" ]] && return 0
  apt-cache show "$pkg" >/dev/null 2>&1 || apt_update "$pkg"
  apt-cache show "$pkg" >/dev/null 2>&1 || die "package '$pkg' is not in the apt sources (Debian 12 main has it)"
  rm -rf "$dir" && mkdir -p "$dir"
  say "downloading $pkg"
  # apt-get download writes into the working directory; its "unsandboxed" notice when run as
  # root is harmless and kept off the output.
  (cd "$dir" && apt-get download -q "$pkg" 2> >(grep -v 'unsandboxed' >&2)) || die "apt-get download $pkg failed"
  local debs=("$dir/${pkg}"_*.deb)
  [[ -f "${debs[0]}" ]] || die "apt-get download $pkg left no .deb in $dir"
  local deb=${debs[0]}
  dpkg-deb -x "$deb" "$dir/root" || die "dpkg-deb -x $deb failed"
  touch "$dir/.unpacked"
}

# Copies one mesh out of its unpacked package (through a tarball member when the path has '!').
extract_mesh() {
  local name=$1 pkg=$2 path=$3 dir="$cache/$2/root" tmp="$dest/.$1.part"
  if [[ "$path" == *'!'* ]]; then
    local tarball="$dir/${path%%!*}" member="${path#*!}"
    [[ -f "$tarball" ]] || die "$pkg has no ${path%%!*} (package layout changed?)"
    tar -xzOf "$tarball" "$member" >"$tmp" 2>/dev/null || { rm -f "$tmp"; die "$member not found in $tarball"; }
  else
    [[ -f "$dir/$path" ]] || die "$pkg has no $path (package layout changed?)"
    cp "$dir/$path" "$tmp"
  fi
  mv "$tmp" "$dest/$name"
}

mkdir -p "$dest"
status=0
for entry in "${meshes[@]}"; do
  IFS='|' read -r name pkg path sha <<<"$entry"
  if ! in_place "$name" "$sha"; then
    [[ $verify_only -eq 1 ]] && { echo "fetch-scenes: $name: missing or wrong checksum" >&2; status=1; continue; }
    unpack_package "$pkg"
    extract_mesh "$name" "$pkg" "$path"
    if ! in_place "$name" "$sha"; then
      # A changed upstream file is not silently accepted: the scenes were framed for this one.
      got=$(sha_of "$dest/$name")
      rm -f "$dest/$name"
      die "$name from $pkg has sha256 $got, expected $sha (the package changed; update the script deliberately)"
    fi
  fi
  printf 'fetch-scenes: ok  %-24s %9d bytes  sha256 %s\n' "$name" "$(stat -c %s "$dest/$name")" "$sha"
done
[[ $status -eq 0 ]] || die "some meshes are missing; run scripts/fetch-scenes.sh"
say "all ${#meshes[@]} meshes verified in ${dest#"$root"/}/"
