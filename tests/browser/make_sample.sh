#!/usr/bin/env bash
# The browser tests' fixture: runs the sample scene and writes its viewer.
#   bash make_sample.sh SINEW VIEWER_SCRIPT OUT_DIR     (exit 77 = skipped: no viewer script)
set -euo pipefail
SINEW=$1 SCRIPT=$2 OUT=$3
[[ -f $SCRIPT ]] || { echo "SKIP: no viewer script $SCRIPT (the build found no npm)"; exit 77; }
rm -rf "$OUT"
"$SINEW" run "$(dirname "$0")/sample_scene.json" --out "$OUT" --quiet
"$SINEW" viewer "$(dirname "$0")/sample_scene.json" --out "$OUT" --title "Sinew viewer test"
