# Start-up stays cheap (docs/performance.md, "Output and start-up"): the sinew executable does
# not link Gmsh (with OpenCASCADE and FLTK, ~90 shared libraries); the Gmsh module
# lib/sinew/gmsh_mesher.so is loaded only to tetrahedralise a surface, and when it cannot be
# loaded the error names the module and the reason.
source "$(dirname "$0")/common.bash"
EXAMPLES="$(cd "$(dirname "$0")/../../examples" && pwd)"

if ldd "$SINEW" | grep -q libgmsh; then fail "sinew loads Gmsh at start-up: $(ldd "$SINEW" | grep libgmsh)"; fi
[[ -f "$(dirname "$SINEW")/lib/sinew/gmsh_mesher.so" ]] || fail "no Gmsh module beside $SINEW"

# The module loads when a scene tetrahedralises a surface.
expect_ok run "$EXAMPLES/features/mesh_tetrahedralize.json" --out "$TMP/tet" --quiet
[[ -f $TMP/tet/frame_0001.vtu ]] || fail "the tetrahedralised scene wrote no frame"

# A module that cannot be loaded: one error line naming it and why (exit 2).
SINEW_GMSH_MODULE="$TMP/none.so" expect_error "none.so (missing)" run "$EXAMPLES/features/mesh_tetrahedralize.json" --out "$TMP/no"
echo "not a shared object" >"$TMP/bad.so"
SINEW_GMSH_MODULE="$TMP/bad.so" expect_error "bad.so" run "$EXAMPLES/features/mesh_tetrahedralize.json" --out "$TMP/bad"
echo "startup: ok"
