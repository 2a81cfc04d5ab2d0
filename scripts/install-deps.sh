#!/usr/bin/env bash
# Installs the Debian 12 packages vkray needs to build, run on lavapipe and test — only those
# missing, so a second run costs a second. Uses sudo when not run as root.
# usage: scripts/install-deps.sh [fuzz]
#   fuzz   also clang and its runtime libraries (libFuzzer, ASan, UBSan) for `make fuzz`; the
#          sanitizer build of `make sanitize` uses g++, whose sanitizer runtimes come with it
set -euo pipefail

packages=(
  cmake make g++ pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools
  libglm-dev libtinyobjloader-dev libstb-dev
  libtbb-dev libcli11-dev nlohmann-json3-dev libgtest-dev libxxhash-dev libopenexr-dev zlib1g-dev
  libembree-dev
  # tests/slurm: a throwaway single-node Slurm (its own configuration and state in a temporary
  # folder; the packages' system services are not used) and jq for checking merged bench reports
  slurmctld slurmd slurm-client munge jq
)
for extra in "$@"; do
  case "$extra" in
    # libclang-rt-14-dev (libFuzzer and the sanitizer runtimes) is only recommended by clang.
    fuzz) packages+=(clang libclang-rt-14-dev) ;;
    *) echo "install-deps: unknown group '$extra' (known: fuzz)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo=(sudo)
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
