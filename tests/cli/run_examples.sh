# Every scene in examples/features/ loads and runs (first frame only, to stay quick), and its
# first frame converges.
source "$(dirname "$0")/common.bash"
FEATURES=$(cd "$(dirname "$0")/../../examples/features" && pwd)
count=0
for scene in "$FEATURES"/*.json; do
  name=$(basename "$scene" .json)
  run run "$scene" --out "$TMP/$name" --frames 1 --quiet
  [[ $RC -eq 0 ]] || fail "$name exited $RC: $(cat "$TMP/err")"
  [[ -s $TMP/$name/summary.json ]] || fail "$name wrote no summary.json"
  "$PY" -c "import json,sys; d=json.load(open(sys.argv[1])); assert d['all_converged'] and d['frames_completed'] == 1" \
    "$TMP/$name/summary.json" || fail "$name: first frame did not converge"
  count=$((count + 1))
done
[[ $count -ge 15 ]] || fail "only $count feature scenes found in $FEATURES"
echo "run_examples: ok ($count scenes)"
