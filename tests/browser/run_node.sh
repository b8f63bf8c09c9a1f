#!/usr/bin/env bash
# Runs one of the viewer's Node checks with the test tools' folder (exit 77 = skipped: no node).
#   bash run_node.sh TOOLS_DIR SCRIPT.mjs ARGS...
set -euo pipefail
export SINEW_BROWSER_TOOLS=$1
shift
command -v node >/dev/null || { echo "SKIP: node not found (Debian package nodejs)"; exit 77; }
exec node "$(dirname "$0")/$1" "${@:2}"
