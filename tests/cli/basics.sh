# --version, --help, every subcommand's --help, and a missing subcommand.
source "$(dirname "$0")/common.bash"

expect_ok --version
grep -Eq '^sinew [0-9]+\.[0-9]+\.[0-9]+$' "$TMP/out" || fail "--version: $(cat "$TMP/out")"

expect_ok --help
for word in materials material; do grep -q "$word" "$TMP/out" || fail "--help lacks $word"; done

for cmd in "materials" "material" "material eval" "material curve"; do
  # shellcheck disable=SC2086
  expect_ok $cmd --help
  grep -q "Usage" "$TMP/out" || fail "$cmd --help prints no usage"
done
expect_ok material eval --help
for flag in --material --param --fn --E --nu --alpha --projection --F --json --mix-lambda \
            --mix-mu --alpha-lambda --alpha-mu; do
  grep -q -- "$flag" "$TMP/out" || fail "material eval --help lacks $flag"
done
expect_ok material curve --help
for flag in --stretch-from --stretch-to --steps --mode --csv; do
  grep -q -- "$flag" "$TMP/out" || fail "material curve --help lacks $flag"
done

expect_error "subcommand"
expect_error "subcommand" material
expect_error "--bogus" materials --bogus
echo "basics: ok"
