# Shared helpers of the CLI tests (sourced; not a test itself). Each test script is run by
# CTest as `bash script.sh /path/to/sinew` and exits non-zero on the first failure.
set -euo pipefail
SINEW=${1:?usage: bash $0 /path/to/sinew}
PY=/usr/bin/python3
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

fail() { echo "FAIL: $*" >&2; exit 1; }

# run ARGS...: runs sinew, leaving stdout, stderr and the exit code in $TMP/out, $TMP/err, $RC.
run() {
  set +e
  "$SINEW" "$@" >"$TMP/out" 2>"$TMP/err"
  RC=$?
  set -e
}

# expect_ok ARGS...: exit 0 and nothing on stderr.
expect_ok() {
  run "$@"
  [[ $RC -eq 0 ]] || fail "sinew $* exited $RC: $(cat "$TMP/err")"
  [[ ! -s $TMP/err ]] || fail "sinew $* wrote to stderr: $(cat "$TMP/err")"
}

# expect_error FIELD ARGS...: exit 2, exactly one line on stderr of the form
# "sinew: error: ..." that mentions FIELD, and nothing on stdout.
expect_error() {
  local field=$1
  shift
  run "$@"
  [[ $RC -eq 2 ]] || fail "sinew $* exited $RC (expected 2); stderr: $(cat "$TMP/err")"
  [[ $(wc -l <"$TMP/err") -eq 1 ]] || fail "sinew $*: expected one stderr line, got: $(cat "$TMP/err")"
  grep -q '^sinew: error: ' "$TMP/err" || fail "sinew $*: bad error format: $(cat "$TMP/err")"
  grep -qF -- "$field" "$TMP/err" || fail "sinew $*: error does not name '$field': $(cat "$TMP/err")"
  [[ ! -s $TMP/out ]] || fail "sinew $*: wrote to stdout on error"
}

# json_check PYTHON_CODE: runs the code with `d` = the JSON on $TMP/out; it asserts.
json_check() {
  "$PY" -c "import json,sys,math
d = json.load(open(sys.argv[1]))
$1" "$TMP/out" || fail "JSON check failed: $1"
}

# scene_error "EXPECTED TEXT" 'SCENE JSON': writes the scene to a fresh folder under $TMP, runs
# it and checks the error line contains "scene.json: " followed by the expected text, and that
# nothing was written (the output folder was not created).
CASE=0
scene_error() {
  local expected=$1 scene=$2
  CASE=$((CASE + 1))
  local dir=$TMP/case$CASE
  mkdir -p "$dir"
  printf '%s\n' "$scene" >"$dir/scene.json"
  expect_error "scene.json: $expected" run "$dir/scene.json" --out "$dir/out"
  [[ ! -e $dir/out ]] || fail "case $CASE ($expected): output folder was created"
}
