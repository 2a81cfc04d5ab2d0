#!/usr/bin/env bash
# Installs the Debian 12 packages vkray needs to build, run on lavapipe and test — only those
# missing, so a second run costs a second. Uses sudo when not run as root.
# usage: [VKRAY_SYSTEM_MESA=1] scripts/install-deps.sh [fuzz]
#   fuzz   also clang and its runtime libraries (libFuzzer, ASan, UBSan) for `make fuzz`; the
#          sanitizer build of `make sanitize` uses g++, whose sanitizer runtimes come with it
#
# Lavapipe (mesa-vulkan-drivers) comes from Debian's bookworm-backports suite, with the libdrm2 and
# libdrm-amdgpu1 it needs: its kernels run faster than on Debian 12's own Mesa 22.3.6
# (docs/performance.md). The suite is added from the mirror of the machine's own Debian source
# (/etc/apt/sources.list.d/*.sources, else /etc/apt/sources.list) when apt does not know it yet. A
# mesa-vulkan-drivers of version MESA_MIN or later, from anywhere, is kept as it is.
#   VKRAY_SYSTEM_MESA=1   keep the distribution's Mesa (any version; vkray runs on 22.3.6 too)
set -euo pipefail

MESA_MIN=24.1
backports=bookworm-backports

packages=(
  cmake make ninja-build g++ pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools
  libglm-dev libtinyobjloader-dev libtinygltf-dev libstb-dev
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

fail() { echo "install-deps: $*" >&2; exit 1; }

installed_version() {  # the installed version of package $1, or nothing
  local s
  s=$(dpkg-query -W -f='${Status} ${Version}' "$1" 2>/dev/null || true)
  [[ "$s" == "install ok installed "* ]] && echo "${s##* }"
  return 0
}

mesa_new_enough() {
  local v
  v=$(installed_version mesa-vulkan-drivers)
  [[ -n "$v" ]] && dpkg --compare-versions "$v" ge "$MESA_MIN"
}

# Whether an apt source of the machine already names the backports suite.
has_backports_source() {
  grep -qsiE "^[[:space:]]*Suites:(.*[[:space:]])?$backports([[:space:]]|\$)" /etc/apt/sources.list.d/*.sources ||
    grep -qsE "^[[:space:]]*deb[[:space:]].*[[:space:]]$backports([[:space:]]|\$)" /etc/apt/sources.list /etc/apt/sources.list.d/*.list
}

# The mirror of the machine's Debian 12 source: its URI on the first line, then its Signed-By field
# as written (a key file, or an inline key over several lines), if it has one.
debian_mirror() {
  local found
  # deb822: the first enabled "deb" entry whose Suites include bookworm itself.
  found=$(awk '
    function done_entry() {
      if (!found && deb && suite && enabled && uri != "") { found = 1; print uri; if (signed != "") print signed }
      deb = suite = 0; enabled = 1; uri = signed = field = ""
    }
    BEGIN { enabled = 1 }
    FNR == 1 { done_entry() }
    /^[ \t]*#/ { next }
    /^[ \t]*$/ { done_entry(); next }
    /^[ \t]/ { if (field == "signed-by") signed = signed "\n" $0; next }
    {
      field = $0; sub(/:.*/, "", field); field = tolower(field)
      value = $0; sub(/^[^:]*:[ \t]*/, "", value)
      if (field == "types") deb = (" " value " ") ~ /[ \t]deb[ \t]/
      else if (field == "suites") suite = (" " value " ") ~ /[ \t]bookworm[ \t]/
      else if (field == "uris") { split(value, u, /[ \t]+/); uri = u[1] }
      else if (field == "signed-by") signed = "Signed-By:" (value == "" ? "" : " " value)
      else if (field == "enabled") enabled = tolower(value) != "no"
    }
    END { done_entry() }' /etc/apt/sources.list.d/*.sources 2>/dev/null || true)
  # One-line format: deb [OPTIONS] URI bookworm COMPONENTS...
  [[ -n "$found" ]] || found=$(awk '
    $1 == "deb" {
      i = 2; opts = ""
      if ($2 ~ /^\[/) { while (i <= NF) { opts = opts " " $i; if ($(i++) ~ /\]$/) break } }
      if ($(i + 1) == "bookworm") {
        print $i
        if (match(opts, /signed-by=[^] \t]+/)) print "Signed-By: " substr(opts, RSTART + 10, RLENGTH - 10)
        exit
      }
    }' /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2>/dev/null || true)
  if [[ -z "$found" ]]; then
    found="http://deb.debian.org/debian"
    [[ -e /usr/share/keyrings/debian-archive-keyring.gpg ]] &&
      found+=$'\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg'
  fi
  echo "$found"
}

add_backports_source() {
  local mirror file=/etc/apt/sources.list.d/$backports.sources
  mirror=$(debian_mirror)
  echo "install-deps: adding Debian's $backports suite from ${mirror%%$'\n'*} to $file"
  printf '%s\n' "# Added by vkray's scripts/install-deps.sh, for mesa-vulkan-drivers (Mesa >= $MESA_MIN)" \
    "Types: deb" "URIs: ${mirror%%$'\n'*}" "Suites: $backports" "Components: main" |
    "${sudo[@]}" tee "$file" >/dev/null || fail "cannot write $file"
  [[ "$mirror" != *$'\n'* ]] || printf '%s\n' "${mirror#*$'\n'}" | "${sudo[@]}" tee -a "$file" >/dev/null ||
    fail "cannot write $file"
}

new_mesa=0  # whether mesa-vulkan-drivers is to come from backports
if [[ "${VKRAY_SYSTEM_MESA:-0}" != 1 ]] && ! mesa_new_enough; then
  new_mesa=1
  codename=$(. /etc/os-release 2>/dev/null && echo "${VERSION_CODENAME:-}")
  [[ "$codename" == bookworm ]] ||
    fail "mesa-vulkan-drivers >= $MESA_MIN comes from $backports on Debian 12, but this is '${codename:-unknown}'; install it yourself or set VKRAY_SYSTEM_MESA=1"
fi
missing=()
for p in "${packages[@]}"; do
  [[ $new_mesa -eq 1 && "$p" == mesa-vulkan-drivers ]] && continue
  [[ -n "$(installed_version "$p")" ]] || missing+=("$p")
done
todo=(${missing[@]+"${missing[@]}"})
[[ $new_mesa -eq 0 ]] || todo+=("mesa-vulkan-drivers (>= $MESA_MIN, from $backports)")
if [[ ${#todo[@]} -eq 0 ]]; then
  echo "install-deps: all ${#packages[@]} packages present (mesa-vulkan-drivers $(installed_version mesa-vulkan-drivers))"
  exit 0
fi

sudo=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || fail "need root or sudo to install: ${todo[*]}"
  sudo=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
if [[ $new_mesa -eq 1 ]] && ! has_backports_source; then
  add_backports_source
fi
"${sudo[@]}" apt-get update -qq || fail "apt-get update failed"
if [[ ${#missing[@]} -gt 0 ]]; then
  echo "install-deps: installing ${missing[*]}"
  "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" || fail "apt-get install failed: ${missing[*]}"
fi
if [[ $new_mesa -eq 1 ]]; then
  echo "install-deps: installing mesa-vulkan-drivers, libdrm2 and libdrm-amdgpu1 from $backports"
  "${sudo[@]}" apt-get install -y -qq --no-install-recommends -t "$backports" mesa-vulkan-drivers libdrm2 libdrm-amdgpu1 ||
    fail "apt-get install -t $backports mesa-vulkan-drivers failed"
  mesa_new_enough ||
    fail "mesa-vulkan-drivers is $(installed_version mesa-vulkan-drivers) after installing from $backports, not >= $MESA_MIN"
  echo "install-deps: mesa-vulkan-drivers $(installed_version mesa-vulkan-drivers)"
fi
