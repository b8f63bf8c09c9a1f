#!/usr/bin/env bash
# Regenerates the example plots of docs/plots.md (docs/img/plot_*.png) from a run of
# examples/stretch_small.json, with the project's own `sinew plot`.
# usage: scripts/make_plot_examples.sh [path/to/sinew]   (default build/sinew; about a minute)
set -euo pipefail
cd "$(dirname "$0")/.."
SINEW=${1:-build/sinew}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
"$SINEW" run examples/stretch_small.json --out "$OUT/run" --quiet
"$SINEW" plot "$OUT/run" --format png --only convergence,reactions,volume --plots "$OUT/plots" >/dev/null
for name in convergence reactions volume; do
  cp "$OUT/plots/$name.png" "docs/img/plot_$name.png"
  echo "docs/img/plot_$name.png"
done
