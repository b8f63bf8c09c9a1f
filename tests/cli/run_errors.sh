# `sinew run` on bad input: one line "sinew: error: <file>: <JSON path>: <reason>", exit code 2,
# and nothing written (the output folder is not created, or a given empty one stays empty).
source "$(dirname "$0")/common.bash"

MESH='"mesh": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}, "cells": [2, 2, 2]}'
MAT='"material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.45}'

# Unknown keys, at every level, with the allowed ones listed.
scene_error "/bogus: unknown field (expected one of: description, mesh" "{$MESH, $MAT, \"bogus\": 1}"
scene_error "/mesh/cels: unknown field" '{"mesh": {"box": {"min": [0,0,0], "max": [1,1,1]}, "cels": [2,2,2]}, '"$MAT}"
scene_error "/mesh/box/centre: unknown field" '{"mesh": {"box": {"min": [0,0,0], "max": [1,1,1], "centre": [0,0,0]}, "cells": [2,2,2]}, '"$MAT}"
scene_error "/material/young: unknown key" "{$MESH, \"material\": {\"family\": \"stable_neo_hookean\", \"young\": 1}}"
scene_error "/material/parameters/kappa: unknown parameter" "{$MESH, \"material\": {\"family\": \"stable_neo_hookean\", \"parameters\": {\"kappa\": 1}}}"
scene_error "/solver/newton/tol: unknown field" "{$MESH, $MAT, \"solver\": {\"newton\": {\"tol\": 1}}}"
scene_error "/boundary/0/motion/speed: unknown field" "{$MESH, $MAT, \"boundary\": [{\"select\": {\"indices\": [0]}, \"motion\": {\"type\": \"translate\", \"per_frame\": [0,0,1], \"speed\": 2}}]}"
scene_error "/loads/wind: unknown field" "{$MESH, $MAT, \"loads\": {\"wind\": [1, 0, 0]}}"
scene_error "/output/png: unknown field" "{$MESH, $MAT, \"output\": {\"png\": true}}"
scene_error "/frames: duplicate key" "{$MESH, $MAT, \"frames\": 2, \"frames\": 3}"
# Wrong types.
scene_error "/frames: must be an integer, got string \"3\"" "{$MESH, $MAT, \"frames\": \"3\"}"
scene_error "/frames: must be an integer, got number 2.5" "{$MESH, $MAT, \"frames\": 2.5}"
scene_error "/density: must be a number, got string" "{$MESH, $MAT, \"density\": \"heavy\"}"
scene_error "/mesh: must be an object, got array" "{\"mesh\": [1, 2], $MAT}"
scene_error "/mesh/cells: must be an array of 3 integers" '{"mesh": {"box": {"min": [0,0,0], "max": [1,1,1]}, "cells": [2,2]}, '"$MAT}"
scene_error "/loads/gravity/2: must be a number, got string" "{$MESH, $MAT, \"loads\": {\"gravity\": [0, 0, \"down\"]}}"
scene_error "/output/vtu: must be true or false" "{$MESH, $MAT, \"output\": {\"vtu\": 1}}"
scene_error "/material/nu: expected a number, got string" "{$MESH, \"material\": {\"family\": \"stable_neo_hookean\", \"E\": 1e5, \"nu\": \"0.3\"}}"
scene_error "/: must be an object, got array" '[1, 2, 3]'
# Missing required fields.
scene_error "/mesh: required field is missing" "{$MAT}"
scene_error "/material: required field is missing" "{$MESH}"
scene_error "/boundary/0/select: required field is missing" "{$MESH, $MAT, \"boundary\": [{\"name\": \"x\"}]}"
scene_error "/boundary/0/motion/per_frame: required field is missing" "{$MESH, $MAT, \"boundary\": [{\"select\": {\"indices\": [0]}, \"motion\": {\"type\": \"translate\"}}]}"
scene_error "/material/nu: missing" "{$MESH, \"material\": {\"family\": \"stable_neo_hookean\", \"E\": 1e5}}"
scene_error "/mesh: give exactly one of box, cylinder, sphere, voxels or file" '{"mesh": {"cells": [2,2,2]}, '"$MAT}"
scene_error "/mesh: give exactly one of cells, cell_size or resolution" '{"mesh": {"box": {"min": [0,0,0], "max": [1,1,1]}}, '"$MAT}"
# NaN and infinity: JSON has no NaN (a string is a wrong type), and 1e999 overflows a double.
scene_error "/density: must be a number, got string \"NaN\"" "{$MESH, $MAT, \"density\": \"NaN\"}"
scene_error "/density: number overflow parsing '1e999'" "{$MESH, $MAT, \"density\": 1e999}"
scene_error "/loads/gravity/1: number overflow parsing '-1e999'" "{$MESH, $MAT, \"loads\": {\"gravity\": [0, -1e999, 0]}}"
scene_error "/material/E: number overflow" "{$MESH, \"material\": {\"family\": \"stable_neo_hookean\", \"E\": 1e400, \"nu\": 0.3}}"
scene_error "malformed JSON" "{$MESH, $MAT, \"density\": NaN}"
# Out-of-range values.
scene_error "/material/nu: must satisfy -1 < nu < 0.5, got 0.5" "{$MESH, \"material\": {\"family\": \"stable_neo_hookean\", \"E\": 1e5, \"nu\": 0.5}}"
scene_error "/material/nu: must satisfy -1 < nu < 0.5, got 0.7" "{$MESH, \"material\": {\"family\": \"stable_neo_hookean\", \"E\": 1e5, \"nu\": 0.7}}"
scene_error "/material/E: must be positive" "{$MESH, \"material\": {\"family\": \"stable_neo_hookean\", \"E\": -1, \"nu\": 0.3}}"
scene_error "/material/alpha: must be positive" "{$MESH, \"material\": {\"family\": \"stable_neo_hookean\", \"E\": 1, \"nu\": 0.3, \"alpha\": 0}}"
scene_error "/density: must be a positive number, got -1000" "{$MESH, $MAT, \"density\": -1000}"
scene_error "/density: must be a positive number, got 0" "{$MESH, $MAT, \"density\": 0}"
scene_error "/mesh/cells/0: must be at least 1, got 0" '{"mesh": {"box": {"min": [0,0,0], "max": [1,1,1]}, "cells": [0,2,2]}, '"$MAT}"
scene_error "/mesh/resolution: must be at least 1, got 0" '{"mesh": {"box": {"min": [0,0,0], "max": [1,1,1]}, "resolution": 0}, '"$MAT}"
scene_error "/mesh/cell_size: must be a positive number" '{"mesh": {"sphere": {"center": [0,0,0], "radius": 1}, "cell_size": -0.1}, '"$MAT}"
scene_error "/mesh/cylinder/radius: must be a positive number, got 0" '{"mesh": {"cylinder": {"center": [0,0,0], "radius": 0, "length": 1}, "resolution": 4}, '"$MAT}"
scene_error "/mesh/box/max: must exceed min" '{"mesh": {"box": {"min": [0,0,0], "max": [1,0,1]}, "cells": [2,2,2]}, '"$MAT}"
scene_error "/mesh/cells: would make" '{"mesh": {"box": {"min": [0,0,0], "max": [1,1,1]}, "cells": [1000,1000,1000]}, '"$MAT}"
scene_error "/mesh/voxels/occupancy: needs dims[0]*dims[1]*dims[2] = 8 entries, got 3" '{"mesh": {"voxels": {"min": [0,0,0], "max": [1,1,1], "dims": [2,2,2], "occupancy": [1,0,1]}}, '"$MAT}"
scene_error "/frames: must be at least 1, got -3" "{$MESH, $MAT, \"frames\": -3}"
scene_error "/frames: must be at least 1, got 0" "{$MESH, $MAT, \"frames\": 0}"
scene_error "/frames: must be at most" "{$MESH, $MAT, \"frames\": 18446744073709551615}"
scene_error "/solver/newton/max_iterations: must be at least 1" "{$MESH, $MAT, \"solver\": {\"newton\": {\"max_iterations\": 0}}}"
scene_error "/solver/linear/kind: unknown value 'lu'" "{$MESH, $MAT, \"solver\": {\"linear\": {\"kind\": \"lu\"}}}"
scene_error "/solver/linear/preconditioner: unknown value 'ilu' (expected one of: jacobi, block_jacobi, lagged_cholesky, multigrid, amg)" "{$MESH, $MAT, \"solver\": {\"linear\": {\"kind\": \"pcg\", \"preconditioner\": \"ilu\"}}}"
scene_error "/solver/linear/tolerance: must be below 1" "{$MESH, $MAT, \"solver\": {\"linear\": {\"kind\": \"pcg\", \"tolerance\": 2}}}"
scene_error "/boundary/0/motion/axis: must be non-zero" "{$MESH, $MAT, \"boundary\": [{\"select\": {\"indices\": [0]}, \"motion\": {\"type\": \"rotate\", \"center\": [0,0,0], \"axis\": [0,0,0], \"degrees_per_frame\": 5}}]}"
scene_error "/boundary/0/motion/keys/1/frame: must be after the previous keyframe" "{$MESH, $MAT, \"boundary\": [{\"select\": {\"indices\": [0]}, \"motion\": {\"type\": \"keyframes\", \"keys\": [{\"frame\": 2}, {\"frame\": 1}]}}]}"
scene_error "/material/family: unknown material 'rubber'" "{$MESH, \"material\": {\"family\": \"rubber\"}}"
# Problems only the built mesh reveals: still before anything is written.
scene_error "/boundary/0/select: selection contains no vertex" "{$MESH, $MAT, \"boundary\": [{\"select\": {\"box\": {\"min\": [5,5,5], \"max\": [6,6,6]}}}]}"
scene_error "/boundary/0/select: vertex index 27 out of range" "{$MESH, $MAT, \"boundary\": [{\"select\": {\"indices\": [27]}}]}"
scene_error "/loads/traction/0/select: selects no boundary face" "{$MESH, $MAT, \"loads\": {\"traction\": [{\"select\": {\"indices\": [0]}, \"traction\": [1, 0, 0]}]}}"
scene_error "/boundary/1/select: vertex 0 is also prescribed along (1, 0, 0) by /boundary/0 with a different motion" "{$MESH, $MAT, \"boundary\": [{\"select\": {\"indices\": [0]}}, {\"select\": {\"indices\": [0, 1]}, \"motion\": {\"type\": \"translate\", \"per_frame\": [0, 0, 1]}}]}"
scene_error "/mesh/voxels/occupancy: no voxel is occupied" '{"mesh": {"voxels": {"min": [0,0,0], "max": [1,1,1], "dims": [1,1,2], "occupancy": [0,0]}}, '"$MAT}"

# Missing and malformed mesh files; relative paths start at the scene's folder.
scene_error "/mesh/file: mesh file not found: " '{"mesh": {"file": "no_such.mesh"}, '"$MAT}"
CASE=$((CASE + 1))
mkdir -p "$TMP/case$CASE/meshes"
printf 'MeshVersionFormatted 1\nDimension 3\nVertices\n2\n0 0 0 0\n' >"$TMP/case$CASE/meshes/broken.mesh"
printf '{"mesh": {"file": "meshes/broken.mesh"}, %s}\n' "$MAT" >"$TMP/case$CASE/scene.json"
expect_error "scene.json: /mesh/file: " run "$TMP/case$CASE/scene.json" --out "$TMP/case$CASE/out"
grep -qF "broken.mesh" "$TMP/err" || fail "mesh error does not name the mesh file: $(cat "$TMP/err")"
[[ ! -e $TMP/case$CASE/out ]] || fail "broken mesh: output folder was created"

# Malformed JSON names the file, line and column.
CASE=$((CASE + 1))
mkdir -p "$TMP/case$CASE"
printf '{\n  "mesh": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}, "cells": [2, 2, 2]},\n  "frames": 2,\n}\n' >"$TMP/case$CASE/scene.json"
expect_error "scene.json: malformed JSON: parse error at line 4, column 1" run "$TMP/case$CASE/scene.json" --out "$TMP/case$CASE/out"
[[ ! -e $TMP/case$CASE/out ]] || fail "malformed JSON: output folder was created"
printf '' >"$TMP/case$CASE/scene.json"
expect_error "malformed JSON" run "$TMP/case$CASE/scene.json" --out "$TMP/case$CASE/out"

# Missing scene file, a folder instead of a file.
expect_error "no_such_scene.json: cannot open scene file" run "$TMP/no_such_scene.json" --out "$TMP/none"
[[ ! -e $TMP/none ]] || fail "missing scene: output folder was created"
expect_error "is a directory" run "$TMP" --out "$TMP/none"

# A given, existing empty output folder stays empty.
CASE=$((CASE + 1))
mkdir -p "$TMP/case$CASE/out"
printf '{%s, %s, "density": -1}\n' "$MESH" "$MAT" >"$TMP/case$CASE/scene.json"
expect_error "/density" run "$TMP/case$CASE/scene.json" --out "$TMP/case$CASE/out"
[[ -z $(ls -A "$TMP/case$CASE/out") ]] || fail "existing output folder is not empty after an error"

# Command-line problems.
GOOD=$TMP/good.json
printf '{%s, %s}\n' "$MESH" "$MAT" >"$GOOD"
expect_error "--frames" run "$GOOD" --out "$TMP/o1" --frames 0
expect_error "--frames" run "$GOOD" --out "$TMP/o1" --frames -2
expect_error "--frames" run "$GOOD" --out "$TMP/o1" --frames two
expect_error "--threads" run "$GOOD" --out "$TMP/o1" --threads 0
[[ ! -e $TMP/o1 ]] || fail "bad option: output folder was created"
expect_error "checkpoint.json: no checkpoint to resume from" run "$GOOD" --out "$TMP/o2" --resume
[[ ! -e $TMP/o2 ]] || fail "--resume without a checkpoint created the output folder"
expect_error "scene" run
echo "run_errors: ok"
