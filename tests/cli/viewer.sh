# `sinew viewer`: a run's folder gets viewer.html and viewer.glb (the page embeds the GLB), as
# with `sinew run --viewer`; a folder without a run or a missing viewer script is a one-line error. A stand-in viewer
# script (SINEW_VIEWER_SCRIPT) keeps this test independent of npm.
source "$(dirname "$0")/common.bash"
SCENE=$(cd "$(dirname "$0")/../browser" && pwd)/sample_scene.json
echo "/* stand-in viewer script */" >"$TMP/viewer.js"
export SINEW_VIEWER_SCRIPT=$TMP/viewer.js
expect_ok run "$SCENE" --out "$TMP/run" --frames 2 --quiet
expect_ok viewer "$SCENE" --out "$TMP/run"
grep -q "viewer of 3 frame(s)" "$TMP/out" || fail "unexpected output: $(cat "$TMP/out")"
[[ -s $TMP/run/viewer.glb && -s $TMP/run/viewer.html ]] || fail "viewer.glb / viewer.html missing"
[[ $(head -c 4 "$TMP/run/viewer.glb") == glTF ]] || fail "viewer.glb is not a GLB"
"$PY" - "$TMP/run" <<'PY' || fail "the page does not embed the GLB"
import base64, re, sys
page = open(sys.argv[1] + "/viewer.html").read()
glb = open(sys.argv[1] + "/viewer.glb", "rb").read()
data = re.search(r'id="sinew-glb">([^<]*)</script>', page).group(1)
assert base64.b64decode(data) == glb and "stand-in viewer script" in page
PY
# `sinew run --viewer` writes the same files at the end of the run; a later run without it
# removes them (they would show the earlier run).
cp "$TMP/run/viewer.glb" "$TMP/first.glb"
expect_ok run "$SCENE" --out "$TMP/run2" --frames 2 --quiet --viewer
cmp -s "$TMP/run2/viewer.glb" "$TMP/first.glb" || fail "run --viewer wrote a different viewer.glb than sinew viewer"
[[ -s $TMP/run2/viewer.html ]] || fail "run --viewer wrote no viewer.html"
expect_ok run "$SCENE" --out "$TMP/run2" --frames 1 --quiet
[[ ! -e $TMP/run2/viewer.glb && ! -e $TMP/run2/viewer.html ]] || fail "a later run left the earlier viewer"
"$PY" -c 'import json,sys; d=json.load(open(sys.argv[1])); d["output"]={"vtu": False}; json.dump(d, open(sys.argv[2],"w"))' \
  "$SCENE" "$TMP/novtu.json"
expect_error "--viewer" run "$TMP/novtu.json" --out "$TMP/run3" --viewer
expect_error "simulation.pvd" viewer "$SCENE" --out "$TMP/no_run"
SINEW_VIEWER_SCRIPT=$TMP/missing.js expect_error "missing.js" viewer "$SCENE" --out "$TMP/run"
expect_error "--fps" viewer "$SCENE" --out "$TMP/run" --fps 0
echo "viewer: ok"
