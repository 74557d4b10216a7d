#!/bin/sh
# Regenerates the pictures in docs/img/ that the README, docs/pictures.md and docs/explore.md show:
# example 1's figures, the comparisons of impact laws and integrators, the heat map of a sweep
# around example 2, and small animations of examples 1 and 3 (reduced width and frame rate so that
# each stays well under 1.5 MB; their height fits the machine).
# Usage: scripts/make-doc-images.sh [path/to/whatnext]   (default: build/whatnext)
set -eu
cd "$(dirname "$0")/.."
WN=${1:-build/whatnext}
if [ ! -x "$WN" ]; then
  echo "make-doc-images: no whatnext at '$WN'; build first (cmake -S . -B build && cmake --build build -j2)" >&2
  exit 2
fi
IMG=docs/img
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$IMG"

"$WN" plot --example 1 --out "$TMP/ex1" --format png,svg -q
cp "$TMP/ex1/overview.png" "$IMG/example1-overview.png"
cp "$TMP/ex1/angles.svg" "$IMG/example1-angles.svg"
cp "$TMP/ex1/energy.png" "$IMG/example1-energy.png"
"$WN" plot --example 2 --compare laws --out "$TMP/ex2" --format png -q
cp "$TMP/ex2/compare_laws.png" "$IMG/example2-compare-laws.png"
"$WN" plot --example 1 --compare integrator --integrator euler --step 0.002 --out "$TMP/ex1e" --format png -q
cp "$TMP/ex1e/compare_integrator.png" "$IMG/example1-compare-euler.png"
"$WN" sweep --example 2 --vary geometry.rope_length=0.62:1.0:40 --vary masses.sandbag=0.2:2.0:40 \
  --out "$TMP/sweep.csv" --heatmap "$IMG/example2-sweep-heatmap.png" --heatmap-value lid_open > /dev/null
"$WN" animate --example 1 --out "$IMG/example1.gif" --width 480 --fps 15 -q
"$WN" animate --example 3 --out "$IMG/example3.gif" --width 400 --fps 10 --max-length 14 -q

# The students' machine (docs/extensions.md): idealised and built, each at its last frame (the radio on).
for m in "ideal examples/konstanz-ideal.toml" "built --example konstanz"; do
  name=${m%% *}
  mkdir -p "$TMP/k-$name"
  # shellcheck disable=SC2086
  "$WN" animate ${m#* } --out "$TMP/k-$name/k.gif" --width 400 --dump-frames "$TMP/k-$name" -q
  cp "$(ls "$TMP/k-$name"/frame*.png | tail -1)" "$IMG/konstanz-$name.png"
done

ls -l "$IMG"
