#!/usr/bin/env bash
# Runs every `build/vkray ...` line of the README's code blocks as written, in the README's order,
# from a scratch folder that sees the build and the scenes where a checkout has them (build/,
# scenes/, scripts/), so a renamed flag, a moved scene or a changed default that breaks an example
# fails here. Synopsis lines (with `[--...]` or `SCENE...`) are skipped; a comment after the
# command is dropped. Each example must exit 0, and an image or file it names with -o must be
# there and not empty. On failure: the README's line, the command and the end of its output.
# usage: readme_examples.sh SOURCE_DIR BUILD_DIR OUT_DIR
set -uo pipefail
src=$1 build=$2 out=$3

rm -rf "$out" && mkdir -p "$out" && cd "$out" || exit 1
ln -s "$build" build && ln -s "$src/scenes" scenes && ln -s "$src/scripts" scripts || exit 1

examples=$(awk '/^```/ { inBlock = !inBlock; next }
                inBlock && /^build\/vkray / && !/\[--|SCENE\.\.\.|DIR\.\.\./ { print FNR ":" $0 }' "$src/README.md")
if [[ -z "$examples" ]]; then
  echo "README.md: no build/vkray example found in its code blocks"
  exit 1
fi

failed=0 count=0
while IFS= read -r entry; do
  line=${entry%%:*}
  cmd=$(sed -E 's/[[:space:]]+#.*$//' <<<"${entry#*:}")
  count=$((count + 1))
  start=$SECONDS
  if ! bash -c "$cmd" >"example-$line.log" 2>&1; then
    echo "README.md:$line: '$cmd' failed; the end of its output:"
    tail -n 5 "example-$line.log"
    failed=1
    continue
  fi
  output=$(sed -nE 's/.*(^| )-o ([^ ]+).*/\2/p' <<<"$cmd")
  if [[ -n "$output" && ! -s "$output" ]]; then
    echo "README.md:$line: '$cmd' exited 0 but wrote no $output"
    failed=1
    continue
  fi
  echo "README.md:$line: ok in $((SECONDS - start)) s: $cmd"
done <<<"$examples"

echo "$count README examples run, $([[ $failed -eq 0 ]] && echo "all passed" || echo "some FAILED")"
exit $failed
