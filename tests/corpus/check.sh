#!/usr/bin/env bash
# The outputs users get, held byte for byte: every line of machines.txt (the paper's examples, the
# radio example, the paper's .inp and 200 random machines with every switch, law and integrator),
# run through the whatnext command, gives a timeline, events JSON, CSV and .dat whose SHA-256
# digests must equal those in digests.txt; so does the sweep CSV of docs/performance.md's grid.
# A refactoring must leave them all alone. A change that means to change an output runs
#   tests/corpus/check.sh build/whatnext --update
# and says in its commit message which outputs changed and why.
set -euo pipefail
cli="$1"
mode="${2:-check}"
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$root"
out="$work/digests.txt"
i=0
while IFS= read -r line; do
  [[ -z "$line" || "$line" == \#* ]] && continue
  i=$((i + 1))
  name=$(printf 'm%03d' "$i")
  eval "args=($line)"
  "$cli" run "${args[@]}" --events "$work/$name.json" --csv "$work/$name.csv" --dat "$work/$name.dat" \
    >"$work/$name.txt"
  for f in txt json csv dat; do
    printf '%s.%s %s\n' "$name" "$f" "$(sha256sum <"$work/$name.$f" | cut -d' ' -f1)" >>"$out"
  done
  rm -f "$work/$name".*
done <"$here/machines.txt"
"$cli" sweep --example 2 --vary geometry.rope_length=0.64:0.80:100 --vary start.sandbag_height=0.3:1.2:100 \
  --out "$work/sweep.csv" >/dev/null
printf 'sweep.csv %s\n' "$(sha256sum <"$work/sweep.csv" | cut -d' ' -f1)" >>"$out"
if [[ "$mode" == "--update" ]]; then
  cp "$out" "$here/digests.txt"
  echo "corpus: $(wc -l <"$out") digests written to tests/corpus/digests.txt"
  exit 0
fi
if diff -u "$here/digests.txt" "$out" >"$work/diff"; then
  echo "corpus: all $(wc -l <"$out") outputs byte-identical"
  exit 0
fi
echo "corpus: outputs differ from tests/corpus/digests.txt (mNNN is line NNN of machines.txt):"
grep '^[-+][^-+]' "$work/diff" | head -40
exit 1
