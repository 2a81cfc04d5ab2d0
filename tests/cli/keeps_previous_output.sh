#!/usr/bin/env bash
# A render whose output cannot be written keeps the previous file byte-identical and leaves no
# temporary file (docs/outputs.md, "How files are written"); one that succeeds replaces the file and
# keeps its mode.
# usage: keeps_previous_output.sh VKRAY SCENE DIR
set -u
vkray=$1 scene=$2 dir=$3
rm -rf "$dir" && mkdir -p "$dir" || exit 1
fail() { echo "FAIL: $*"; echo "--- stderr:"; echo "$err"; exit 1; }
previous() { printf 'the previous image, not a PNG\n' >"$dir/prev.png"; cp "$dir/prev.png" "$dir/expected"; }
check_kept() {  # RC ERR-PATTERN
    [[ $rc -eq $1 ]] || fail "exit code $rc, expected $1"
    [[ $(grep -c '^error: ' <<<"$err") -eq 1 ]] || fail "expected exactly one 'error: ' line"
    grep -E -q -- "^error: $2" <<<"$err" || fail "error line does not match '$2'"
    cmp -s "$dir/prev.png" "$dir/expected" || fail "prev.png changed"
    leftover=$(find "$dir" -name '.*.vkray-*')
    [[ -z $leftover ]] || fail "temporary left: $leftover"
}
render() { timeout 120 "$vkray" render "$scene" --cpu --size 32x32 --quiet "$@"; }

# A disk that fills: with RLIMIT_FSIZE at 0 (SIGXFSZ ignored) every write fails, as on a full disk.
previous
err=$( (trap '' XFSZ; ulimit -f 0; render -o "$dir/prev.png") 2>&1 >/dev/null ); rc=$?
check_kept 1 "$dir/prev\\.png: write failed: File too large"

# A link to a device that fails: written through, the link and the device both stay.
if [[ -e /dev/full ]]; then
    ln -s /dev/full "$dir/full.png"
    err=$(render -o "$dir/full.png" 2>&1 >/dev/null); rc=$?
    check_kept 1 "$dir/full\\.png: write failed: No space left on device"
    [[ -L $dir/full.png && -c /dev/full ]] || fail "the link or /dev/full is gone"
fi

# A write that succeeds replaces the file whole and keeps its mode bits.
chmod 0640 "$dir/prev.png"
err=$(render -o "$dir/prev.png" 2>&1 >/dev/null); rc=$?
[[ $rc -eq 0 ]] || fail "exit code $rc on a plain render"
[[ $(head -c 4 "$dir/prev.png" | od -An -c | tr -d ' ') == '211PNG' ]] || fail "prev.png is not the new PNG"
[[ $(stat -c %a "$dir/prev.png") == 640 ]] || fail "mode $(stat -c %a "$dir/prev.png"), expected 640"
[[ -z $(find "$dir" -name '.*.vkray-*') ]] || fail "temporary left after a render"
echo "ok: previous output kept on failure, replaced on success"
