// Scene files: what each field parses to, the defaults, and the validation errors (each names
// the file, the JSON path and the reason); relative mesh paths; the mesh each source builds;
// every example scene loads.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "io_test_support.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/model/scene.hpp"

namespace sinew {
namespace {

using nlohmann::json;
using test::error_message;
using test::TempDir;

const json kMesh = json::parse(R"({"box": {"min": [0, 0, 0], "max": [1, 1, 1]}, "cells": [2, 2, 2]})");
const json kMaterial = json::parse(R"({"family": "stable_neo_hookean", "E": 1e5, "nu": 0.45})");

json minimal() { return {{"mesh", kMesh}, {"material", kMaterial}}; }

// A scene with `patch` merged into the minimal one (JSON merge patch: null removes a key).
json with(const json& patch) {
  json j = minimal();
  j.merge_patch(patch);
  return j;
}

std::string parse_error(const json& j) {
  return error_message([&] { parse_scene(j, "dir/scene.json"); });
}

std::filesystem::path examples_dir() { return test::data_path("../../examples"); }

TEST(Scene, MinimalSceneGetsTheDocumentedDefaults) {
  const Scene s = parse_scene(minimal(), "dir/scene.json");
  EXPECT_EQ(s.file, std::filesystem::path("dir/scene.json"));
  ASSERT_TRUE(std::holds_alternative<BoxShape>(s.mesh.source));
  EXPECT_EQ(*s.mesh.cells, Eigen::Vector3i(2, 2, 2));
  EXPECT_EQ(s.mesh.element, ElementKind::Hex8);
  EXPECT_EQ(s.material.family, "stable_neo_hookean");
  ASSERT_TRUE(s.material.target.has_value());
  EXPECT_EQ(s.material.target->E, 1e5);
  EXPECT_EQ(s.material.target->nu, 0.45);
  EXPECT_EQ(s.density, 1000.0);
  EXPECT_TRUE(s.boundary.empty());
  EXPECT_EQ(s.gravity, Eigen::Vector3d::Zero());
  EXPECT_TRUE(s.point_loads.empty());
  EXPECT_TRUE(s.tractions.empty());
  EXPECT_EQ(s.frames, 1);
  EXPECT_TRUE(s.output.vtu);
  EXPECT_TRUE(s.output.obj);
  EXPECT_EQ(s.output.every, 1);
  EXPECT_EQ(s.solver.newton.test, ConvergenceTest::Relative);  // dimensionless by default
  EXPECT_EQ(s.solver.newton.residual_tolerance, 1e-6);
  EXPECT_EQ(s.solver.newton.step_tolerance, 1e-4);
  EXPECT_EQ(s.solver.newton.max_iterations, 100);
  EXPECT_EQ(s.solver.linear.kind, "cholmod");
  EXPECT_EQ(s.solver.linear.preconditioner, "block_jacobi");
  EXPECT_FALSE(s.solver.newton.eisenstat_walker);
  EXPECT_EQ(s.solver.projection, Projection::Clamp);
  EXPECT_EQ(s.description, "");
}

TEST(Scene, EveryFieldIsRead) {
  const json j = json::parse(R"({
    "description": "all of it",
    "mesh": {"cylinder": {"center": [1, 2, 3], "radius": 0.5, "length": 2, "axis": "y"}, "cell_size": 0.25,
             "element": "tet"},
    "material": {"family": "neo_hookean", "parameters": {"mu": 2, "lambda": 3}, "alpha": 1.5},
    "density": 1200,
    "boundary": [
      {"name": "a", "select": {"plane": {"point": [0, 0, 0], "normal": [0, -1, 0]}}},
      {"select": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}}, "motion": {"type": "translate", "per_frame": [0, 0.1, 0]}},
      {"select": {"indices": [3, 1]}, "motion": {"type": "rotate", "center": [1, 1, 1], "axis": [0, 0, 2], "degrees_per_frame": 90}},
      {"select": {"indices": [0]}, "motion": {"type": "keyframes", "keys": [
        {"frame": 0}, {"frame": 2.5, "translation": [1, 0, 0], "rotation": {"axis": [1, 0, 0], "degrees": 180}}]}}
    ],
    "loads": {"gravity": [0, 0, -9.81],
              "point": [{"select": {"indices": [2]}, "force": [1, 2, 3]}],
              "traction": [{"select": {"plane": {"point": [0, 0, 0], "normal": [0, 1, 0]}}, "traction": [0, 5, 0]}]},
    "solver": {"newton": {"convergence": "absolute", "tolerance": 1e-6, "relative_tolerance": 1e-3, "max_iterations": 7, "line_search_steps": 9},
               "linear": {"kind": "pcg", "preconditioner": "jacobi", "tolerance": 1e-5, "eisenstat_walker": true,
                          "max_iterations": 123},
               "projection": "abs"},
    "frames": 5,
    "output": {"vtu": false, "obj": true, "every": 3}
  })");
  const Scene s = parse_scene(j, "scene.json");
  EXPECT_EQ(s.description, "all of it");
  const auto& c = std::get<CylinderShape>(s.mesh.source);
  EXPECT_EQ(c.center, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(c.radius, 0.5);
  EXPECT_EQ(c.length, 2.0);
  EXPECT_EQ(c.axis, 1);
  EXPECT_EQ(*s.mesh.cell_size, 0.25);
  EXPECT_EQ(s.mesh.element, ElementKind::Tet4);
  EXPECT_EQ(s.material.family, "neo_hookean");
  EXPECT_EQ(s.material.parameters.values.at("mu"), 2.0);
  EXPECT_EQ(s.material.alpha, 1.5);
  EXPECT_EQ(s.density, 1200.0);
  ASSERT_EQ(s.boundary.size(), 4u);
  EXPECT_EQ(s.boundary[0].name, "a");
  EXPECT_EQ(s.boundary[1].name, "/boundary/1");  // unnamed: its JSON path
  EXPECT_TRUE(std::holds_alternative<Pinned>(s.boundary[0].motion));
  EXPECT_EQ(std::get<Translation>(s.boundary[1].motion).per_frame, Eigen::Vector3d(0, 0.1, 0));
  const auto& rot = std::get<Rotation>(s.boundary[2].motion);
  EXPECT_DOUBLE_EQ(rot.angle_per_frame, std::numbers::pi / 2);
  EXPECT_EQ(std::get<IndexSelector>(s.boundary[2].select).indices, (std::vector<int>{3, 1}));
  const auto& keys = std::get<Keyframes>(s.boundary[3].motion).keys;
  ASSERT_EQ(keys.size(), 2u);
  EXPECT_EQ(keys[1].frame, 2.5);
  EXPECT_NEAR(keys[1].rotation.angularDistance(Eigen::Quaterniond::Identity()), std::numbers::pi, 1e-12);
  EXPECT_EQ(s.gravity, Eigen::Vector3d(0, 0, -9.81));
  ASSERT_EQ(s.point_loads.size(), 1u);
  EXPECT_EQ(s.point_loads[0].force, Eigen::Vector3d(1, 2, 3));
  ASSERT_EQ(s.tractions.size(), 1u);
  EXPECT_EQ(s.tractions[0].traction, Eigen::Vector3d(0, 5, 0));
  EXPECT_EQ(s.solver.newton.test, ConvergenceTest::Absolute);
  EXPECT_EQ(s.solver.newton.absolute_tolerance, 1e-6);
  EXPECT_EQ(s.solver.newton.relative_tolerance, 1e-3);
  EXPECT_EQ(s.solver.newton.max_iterations, 7);
  EXPECT_EQ(s.solver.newton.max_line_search_steps, 9);
  EXPECT_EQ(s.solver.linear.kind, "pcg");
  EXPECT_EQ(s.solver.linear.preconditioner, "jacobi");
  EXPECT_EQ(s.solver.newton.linear_tolerance, 1e-5);
  EXPECT_TRUE(s.solver.newton.eisenstat_walker);
  EXPECT_EQ(s.solver.linear.max_iterations, 123);
  EXPECT_EQ(s.solver.projection, Projection::Abs);
  EXPECT_EQ(s.frames, 5);
  EXPECT_FALSE(s.output.vtu);
  EXPECT_TRUE(s.output.obj);
  EXPECT_EQ(s.output.every, 3);
}

TEST(Scene, MixMaterialIsRead) {
  json j = minimal();
  j["material"] = json::parse(R"({"mix": {"lambda_family": "stable_neo_hookean_eq13",
      "mu_family": "linear_corotational", "alpha_mu": 2}, "E": 10, "nu": 0.3})");
  const Scene s = parse_scene(j, "scene.json");
  ASSERT_TRUE(s.material.mix.has_value());
  EXPECT_EQ(s.material.mix->mu_family, "linear_corotational");
  EXPECT_EQ(s.material.mix->alpha_mu, 2.0);
  EXPECT_EQ(s.material.mix->alpha_lambda, 1.0);
}

struct BadScene {
  const char* patch;     // merged into the minimal scene
  const char* expected;  // "path: reason" after "dir/scene.json: "
};

class SceneValidation : public ::testing::TestWithParam<BadScene> {};

TEST_P(SceneValidation, NamesFilePathAndReason) {
  const BadScene& c = GetParam();
  const std::string message = parse_error(with(json::parse(c.patch)));
  const std::string expected = std::string("dir/scene.json: ") + c.expected;
  EXPECT_EQ(message.rfind(expected, 0), 0u) << "got: " << message << "\nexpected to start with: " << expected;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    Scene, SceneValidation,
    ::testing::Values(
        // unknown keys, at several levels
        BadScene{R"({"meshh": 1})", "/meshh: unknown field (expected one of: description, mesh, material"},
        BadScene{R"({"mesh": {"box": {"min": [0,0,0], "max": [1,1,1], "size": 1}}})", "/mesh/box/size: unknown field"},
        BadScene{R"({"material": {"nu2": 1}})", "/material/nu2: unknown key"},
        BadScene{R"({"solver": {"linear": {"precond": "jacobi"}}})", "/solver/linear/precond: unknown field"},
        BadScene{R"({"boundary": [{"select": {"indices": [0], "plane": 1}}]})", "/boundary/0/select: give exactly one of box, plane or indices"},
        BadScene{R"({"boundary": [{"select": {"planes": 1}}]})", "/boundary/0/select/planes: unknown field"},
        BadScene{R"({"loads": {"point": [{"select": {"indices": [0]}, "force": [0,0,1], "f": 1}]}})", "/loads/point/0/f: unknown field"},
        // wrong types
        BadScene{R"({"frames": "2"})", "/frames: must be an integer, got string \"2\""},
        BadScene{R"({"frames": 1.5})", "/frames: must be an integer, got number 1.5"},
        BadScene{R"({"density": [1]})", "/density: must be a number, got array [1]"},
        BadScene{R"({"boundary": {"select": 1}})", "/boundary: must be an array, got object"},
        BadScene{R"({"boundary": [3]})", "/boundary/0: must be an object, got number 3"},
        BadScene{R"({"loads": {"gravity": [0, 0]}})", "/loads/gravity: must be an array of 3 numbers"},
        BadScene{R"({"loads": {"gravity": [0, 0, true]}})", "/loads/gravity/2: must be a number, got boolean true"},
        BadScene{R"({"output": {"obj": "yes"}})", "/output/obj: must be true or false, got string \"yes\""},
        BadScene{R"({"mesh": {"cells": [2, 2.5, 2]}})", "/mesh/cells/1: must be an integer, got number 2.5"},
        BadScene{R"({"material": {"E": "1e5"}})", "/material/E: expected a number, got string"},
        BadScene{R"({"description": 5})", "/description: must be a string, got number 5"},
        BadScene{R"({"solver": {"projection": 1}})", "/solver/projection: must be a string"},
        // missing required fields
        BadScene{R"({"mesh": null})", "/mesh: required field is missing"},
        BadScene{R"({"material": null})", "/material: required field is missing"},
        BadScene{R"({"material": {"E": null}})", "/material/E: missing"},
        BadScene{R"({"material": {"family": null, "E": null, "nu": null}})", "/material/family: missing required key"},
        BadScene{R"({"mesh": {"box": {"max": [1,1,1], "min": null}}})", "/mesh/box/min: required field is missing"},
        BadScene{R"({"mesh": {"cells": null}})", "/mesh: give exactly one of cells, cell_size or resolution"},
        BadScene{R"({"boundary": [{"name": "x"}]})", "/boundary/0/select: required field is missing"},
        BadScene{R"({"boundary": [{"select": {"indices": [0]}, "motion": {"type": "rotate", "center": [0,0,0], "axis": [0,0,1]}}]})",
                 "/boundary/0/motion/degrees_per_frame: required field is missing"},
        BadScene{R"({"boundary": [{"select": {"indices": [0]}, "motion": {"type": "keyframes"}}]})", "/boundary/0/motion/keys: required field is missing"},
        BadScene{R"({"loads": {"traction": [{"select": {"indices": [0]}}]}})", "/loads/traction/0/traction: required field is missing"},
        // out-of-range values
        BadScene{R"({"material": {"nu": 0.5}})", "/material/nu: must satisfy -1 < nu < 0.5, got 0.5"},
        BadScene{R"({"material": {"nu": 0.5000001}})", "/material/nu: must satisfy -1 < nu < 0.5"},
        BadScene{R"({"material": {"nu": -1}})", "/material/nu: must satisfy -1 < nu < 0.5, got -1"},
        BadScene{R"({"material": {"E": 0}})", "/material/E: must be positive, got 0"},
        BadScene{R"({"material": {"alpha": -2}})", "/material/alpha: must be positive, got -2"},
        BadScene{R"({"material": {"family": "nope"}})", "/material/family: unknown material 'nope'"},
        BadScene{R"({"material": {"family": "hill", "functions": {"f": "log(x"}}})", "/material: material 'hill': "},
        BadScene{R"({"density": -1})", "/density: must be a positive number, got -1"},
        BadScene{R"({"density": 0})", "/density: must be a positive number, got 0"},
        BadScene{R"({"frames": 0})", "/frames: must be at least 1, got 0"},
        BadScene{R"({"frames": -5})", "/frames: must be at least 1, got -5"},
        BadScene{R"({"frames": 1000001})", "/frames: must be at most 1000000, got 1000001"},
        BadScene{R"({"frames": 9223372036854775807})", "/frames: must be at most 2147483647"},
        BadScene{R"({"frames": 18446744073709551615})", "/frames: must be at most 2147483647, got 18446744073709551615"},
        BadScene{R"({"mesh": {"cells": [0, 1, 1]}})", "/mesh/cells/0: must be at least 1, got 0"},
        BadScene{R"({"mesh": {"cells": [1, 1, 2000000]}})", "/mesh/cells/2: must be at most 1000000"},
        BadScene{R"({"mesh": {"cells": [1000, 1000, 1000]}})", "/mesh/cells: would make 1e+09 cells"},
        BadScene{R"({"mesh": {"cells": null, "resolution": 0}})", "/mesh/resolution: must be at least 1, got 0"},
        BadScene{R"({"mesh": {"cells": null, "cell_size": 0}})", "/mesh/cell_size: must be a positive number, got 0"},
        BadScene{R"({"mesh": {"cells": null, "resolution": 2, "cell_size": 1}})", "/mesh: give exactly one of cells, cell_size or resolution"},
        BadScene{R"({"mesh": {"box": {"min": [0,0,0], "max": [1,-1,1]}}})", "/mesh/box/max: must exceed min in every coordinate"},
        BadScene{R"({"mesh": {"box": null, "sphere": {"center": [0,0,0], "radius": -1}}})", "/mesh/sphere/radius: must be a positive number, got -1"},
        BadScene{R"({"mesh": {"box": null, "cylinder": {"center": [0,0,0], "radius": 1, "length": 1, "axis": "w"}}})",
                 "/mesh/cylinder/axis: unknown value 'w' (expected one of: x, y, z)"},
        BadScene{R"({"mesh": {"box": null, "cells": null, "sphere": {"center": [0,0,0], "radius": 1}}})", "/mesh: give exactly one of cells"},
        BadScene{R"({"mesh": {"box": null, "voxels": {"min": [0,0,0], "max": [1,1,1], "dims": [2,1,1], "occupancy": [1,1]}}})",
                 "/mesh/cells: a voxel shape's resolution is its dims"},
        BadScene{R"({"mesh": {"box": null, "cells": null, "voxels": {"min": [0,0,0], "max": [1,1,1], "dims": [2,1,1], "occupancy": [1]}}})",
                 "/mesh/voxels/occupancy: needs dims[0]*dims[1]*dims[2] = 2 entries, got 1"},
        BadScene{R"({"mesh": {"box": null, "cells": null, "voxels": {"min": [0,0,0], "max": [1,1,1], "dims": [2,1,1], "occupancy": [1, -1]}}})",
                 "/mesh/voxels/occupancy/1: must be at least 0, got -1"},
        BadScene{R"({"mesh": {"element": "prism"}})", "/mesh/element: unknown value 'prism' (expected one of: hex, tet)"},
        BadScene{R"({"boundary": [{"select": {"indices": []}}]})", "/boundary/0/select/indices: must not be empty"},
        BadScene{R"({"boundary": [{"select": {"indices": [-1]}}]})", "/boundary/0/select/indices/0: must be at least 0, got -1"},
        BadScene{R"({"boundary": [{"select": {"box": {"min": [1,1,1], "max": [0,0,0]}}}]})", "/boundary/0/select/box/max: must be >= min"},
        BadScene{R"({"boundary": [{"select": {"plane": {"point": [0,0,0], "normal": [0,0,0]}}}]})",
                 "/boundary/0/select/plane/normal: must be non-zero"},
        BadScene{R"({"boundary": [{"select": {"indices": [0]}, "motion": {"type": "spin"}}]})",
                 "/boundary/0/motion/type: unknown value 'spin' (expected one of: pinned, translate, rotate, keyframes, displace)"},
        BadScene{R"({"boundary": [{"select": {"indices": [0]}, "motion": {"type": "pinned", "per_frame": [0,0,1]}}]})",
                 "/boundary/0/motion/per_frame: does not apply here"},
        BadScene{R"({"boundary": [{"select": {"indices": [0]}, "motion": {"type": "keyframes", "keys": []}}]})",
                 "/boundary/0/motion/keys: needs at least one keyframe"},
        BadScene{R"({"boundary": [{"select": {"indices": [0]}, "motion": {"type": "keyframes", "keys": [{"frame": 1}, {"frame": 1}]}}]})",
                 "/boundary/0/motion/keys/1/frame: must be after the previous keyframe's (1 <= 1)"},
        BadScene{R"({"boundary": [{"select": {"indices": [0]}, "motion": {"type": "keyframes", "keys": [{"frame": 1, "rotation": {"axis": [0,0,0], "degrees": 3}}]}}]})",
                 "/boundary/0/motion/keys/0/rotation/axis: must be non-zero"},
        BadScene{R"({"solver": {"newton": {"convergence": "absolute", "tolerance": 0}}})", "/solver/newton/tolerance: must be a positive number, got 0"},
        BadScene{R"({"solver": {"newton": {"convergence": "absolute", "relative_tolerance": 1}}})", "/solver/newton/relative_tolerance: must be in [0, 1)"},
        BadScene{R"({"solver": {"newton": {"tolerance": 1e-3}}})", "/solver/newton/tolerance: is a setting of the absolute test"},
        BadScene{R"({"solver": {"newton": {"convergence": "absolute", "step_tolerance": 1e-3}}})", "/solver/newton/step_tolerance: is a setting of the relative test"},
        BadScene{R"({"solver": {"newton": {"residual_tolerance": 2}}})", "/solver/newton/residual_tolerance: must be below 1"},
        BadScene{R"({"solver": {"newton": {"max_iterations": 0}}})", "/solver/newton/max_iterations: must be at least 1, got 0"},
        BadScene{R"({"solver": {"linear": {"tolerance": 1.5}}})", "/solver/linear/tolerance: must be below 1"},
        BadScene{R"({"solver": {"linear": {"kind": "pardiso"}}})", "/solver/linear/kind: unknown value 'pardiso'"},
        BadScene{R"({"solver": {"linear": {"preconditioner": "ilu"}}})", "/solver/linear/preconditioner: unknown value 'ilu'"},
        BadScene{R"({"solver": {"projection": "flip"}})", "/solver/projection: unknown value 'flip' (expected one of: clamp, abs, none)"},
        BadScene{R"({"output": {"every": 0}})", "/output/every: must be at least 1, got 0"}));

TEST(Scene, RootMustBeAnObject) {
  EXPECT_EQ(parse_error(json::array({1, 2})), "dir/scene.json: /: must be an object, got array [1,2]");
  json j = minimal();
  j["density"] = nullptr;  // null is a value of the wrong type, not an absent field
  EXPECT_EQ(parse_error(j), "dir/scene.json: /density: must be a number, got null null");
}

TEST(Scene, MeshFileOptionsThatDoNotApplyAreRejected) {
  TempDir dir;
  std::filesystem::copy_file(test::data_path("hex2.mesh"), dir / "m.mesh");
  json j = minimal();
  j["mesh"] = {{"file", "m.mesh"}, {"cells", {1, 1, 1}}};
  EXPECT_NE(error_message([&] { parse_scene(j, dir / "s.json"); }).find("/mesh/cells: a mesh file has its own resolution"),
            std::string::npos);
  j["mesh"] = {{"file", "m.mesh"}, {"element", "tet"}};
  EXPECT_NE(error_message([&] { parse_scene(j, dir / "s.json"); }).find("/mesh/element: a mesh file's element kind comes from the file"),
            std::string::npos);
}

// ---- load_scene: files, JSON syntax, numbers JSON cannot hold

TEST(SceneFile, MissingFileIsNamed) {
  TempDir dir;
  const std::string m = error_message([&] { load_scene(dir / "nope.json"); });
  test::expect_contains(m, {"nope.json", "cannot open scene file"});
  test::expect_contains(error_message([&] { load_scene(dir.path()); }), {"is a directory"});
}

TEST(SceneFile, MalformedJsonNamesLineAndColumn) {
  TempDir dir;
  const auto f = dir.write("scene.json", "{\n  \"frames\": 1,\n  \"mesh\": {]\n}\n");
  const std::string m = error_message([&] { load_scene(f); });
  EXPECT_EQ(m.rfind(f.string() + ": malformed JSON: parse error at line 3, column 12", 0), 0u) << m;
  EXPECT_EQ(m.find("[json.exception"), std::string::npos) << m;
  test::expect_contains(error_message([&] { load_scene(dir.write("empty.json", "")); }), {"empty.json: malformed JSON"});
  test::expect_contains(error_message([&] { load_scene(dir.write("nan.json", R"({"density": NaN})")); }),
                        {"nan.json: malformed JSON"});
}

TEST(SceneFile, NumbersBeyondADoubleNameTheirPath) {
  // nlohmann rejects 1e999 while parsing (it does not silently become infinity); the error
  // still names the JSON path of the value.
  TempDir dir;
  const auto f = dir.write("scene.json", R"({"mesh": {"box": {"min": [0, 0, 0], "max": [1, 1e999, 1]}}})");
  EXPECT_EQ(error_message([&] { load_scene(f); }),
            f.string() + ": /mesh/box/max/1: number overflow parsing '1e999' (numbers must be finite doubles)");
  const auto g = dir.write("g.json", R"({"a": [1, 2, {"b": -1e400}]})");
  test::expect_contains(error_message([&] { load_scene(g); }), {"g.json: /a/2/b: number overflow parsing '-1e400'"});
  // Large but finite numbers are numbers: the range checks judge them.
  const auto h = dir.write("h.json", with({{"density", 1e308}}).dump());
  EXPECT_EQ(load_scene(h).density, 1e308);
  const auto k = dir.write("k.json", with({{"material", {{"family", "stable_neo_hookean"}, {"E", 1e5}, {"nu", 1e300}}}}).dump());
  test::expect_contains(error_message([&] { load_scene(k); }), {"k.json: /material/nu: must satisfy -1 < nu < 0.5"});
}

TEST(SceneFile, DuplicateKeysAreRejected) {
  TempDir dir;
  const auto f = dir.write("scene.json", R"({"mesh": {"box": {"min": [0,0,0], "max": [1,1,1], "min": [0,0,0]}}})");
  EXPECT_EQ(error_message([&] { load_scene(f); }),
            f.string() + ": /mesh/box/min: duplicate key (JSON objects need unique keys)");
}

TEST(SceneFile, RelativeMeshPathsStartAtTheScenesFolder) {
  TempDir dir;
  std::filesystem::create_directories(dir / "scenes/meshes");
  std::filesystem::create_directories(dir / "shared");
  std::filesystem::copy_file(test::data_path("hex2.mesh"), dir / "scenes/meshes/two.mesh");
  std::filesystem::copy_file(test::data_path("tet5.mesh"), dir / "shared/five.mesh");
  json j = minimal();
  j["mesh"] = {{"file", "meshes/two.mesh"}};
  const auto scene_file = dir.write("scenes/a.json", j.dump());
  // Load from a working folder where the relative path does not exist.
  const auto cwd = std::filesystem::current_path();
  std::filesystem::current_path(dir / "shared");
  Scene s;
  EXPECT_NO_THROW(s = load_scene(scene_file));
  std::filesystem::current_path(cwd);
  EXPECT_EQ(std::get<MeshFile>(s.mesh.source).path, dir / "scenes/meshes/two.mesh");
  EXPECT_EQ(build_scene_mesh(s).num_elements(), 2);
  // Parent folders and absolute paths work too.
  j["mesh"] = {{"file", "../shared/five.mesh"}};
  EXPECT_EQ(build_scene_mesh(load_scene(dir.write("scenes/b.json", j.dump()))).num_elements(), 5);
  j["mesh"] = {{"file", (dir / "shared/five.mesh").string()}};
  EXPECT_EQ(build_scene_mesh(load_scene(dir.write("scenes/c.json", j.dump()))).kind, ElementKind::Tet4);
  // A missing file is reported at load time, with the path it looked for.
  j["mesh"] = {{"file", "meshes/five.mesh"}};
  const auto d = dir.write("scenes/d.json", j.dump());
  EXPECT_EQ(error_message([&] { load_scene(d); }),
            d.string() + ": /mesh/file: mesh file not found: " + (dir / "scenes/meshes/five.mesh").string() +
                " (relative paths start at the scene file's folder)");
}

TEST(SceneFile, BrokenMeshFileIsReportedWithTheJsonPath) {
  TempDir dir;
  dir.write("bad.mesh", "MeshVersionFormatted 1\nDimension 3\nVertices\n1\n0 0 0 0\nHexahedra\n1\n1 1 1 1 1 1 1 1 0\nEnd\n");
  json j = minimal();
  j["mesh"] = {{"file", "bad.mesh"}};
  const Scene s = load_scene(dir.write("s.json", j.dump()));
  const std::string m = error_message([&] { build_scene_mesh(s); });
  EXPECT_EQ(m.rfind((dir / "s.json").string() + ": /mesh/file: " + (dir / "bad.mesh").string(), 0), 0u) << m;
}

// ---- the meshes the sources build

double mesh_volume(const VolumeMesh& mesh) {
  double v = 0.0;
  const Discretization disc(mesh);
  for (Eigen::Index e = 0; e < disc.num_elements(); ++e) v += disc.rest_volume(e);
  return v;
}

VolumeMesh built(const json& mesh) { return build_scene_mesh(parse_scene(with({{"mesh", mesh}}), "s.json")); }

TEST(SceneMesh, LatticesFollowTheirShapeAndResolution) {
  const VolumeMesh box = built(json::parse(R"({"box": {"min": [0,0,0], "max": [2,1,1]}, "cells": [4, 2, 3]})"));
  EXPECT_EQ(box.num_elements(), 24);
  EXPECT_EQ(box.num_vertices(), 5 * 3 * 4);
  EXPECT_NEAR(mesh_volume(box), 2.0, 1e-12);
  // resolution: cells along the longest side; the others follow the same cell size.
  const VolumeMesh res = built(json::parse(R"({"box": {"min": [0,0,0], "max": [2,1,1]}, "cells": null, "resolution": 4})"));
  EXPECT_EQ(res.num_elements(), 4 * 2 * 2);
  const VolumeMesh size = built(json::parse(R"({"box": {"min": [0,0,0], "max": [2,1,1]}, "cells": null, "cell_size": 0.25})"));
  EXPECT_EQ(size.num_elements(), 8 * 4 * 4);
  const VolumeMesh tets = built(json::parse(R"({"box": {"min": [0,0,0], "max": [2,1,1]}, "cells": [4, 2, 3], "element": "tet"})"));
  EXPECT_EQ(tets.kind, ElementKind::Tet4);
  EXPECT_EQ(tets.num_elements(), 6 * 24);
  EXPECT_NEAR(mesh_volume(tets), 2.0, 1e-12);
  // Curved shapes: cells whose centre lies inside; the volume converges to the shape's.
  const VolumeMesh ball = built(json::parse(R"({"box": null, "cells": null, "sphere": {"center": [1,2,3], "radius": 1}, "resolution": 24})"));
  EXPECT_NEAR(mesh_volume(ball), 4.0 / 3.0 * std::numbers::pi, 0.03 * 4.0);
  EXPECT_NEAR(ball.vertices.col(1).mean(), 2.0, 1e-9);
  const VolumeMesh cyl = built(json::parse(
      R"({"box": null, "cells": null, "cylinder": {"center": [0,0,0], "radius": 0.5, "length": 3, "axis": "x"}, "cell_size": 0.05})"));
  EXPECT_NEAR(mesh_volume(cyl), std::numbers::pi * 0.25 * 3.0, 0.02 * 2.4);
  EXPECT_NEAR(cyl.vertices.col(0).maxCoeff() - cyl.vertices.col(0).minCoeff(), 3.0, 1e-9);
  EXPECT_LE(cyl.vertices.col(1).maxCoeff(), 0.5 + 1e-9);
}

TEST(SceneMesh, VoxelsKeepExactlyTheOccupiedCells) {
  // x fastest: the L of mesh_voxels.json, cells of 0.2.
  const VolumeMesh m = built(json::parse(R"({"box": null, "cells": null, "voxels": {"min": [0,0,0], "max": [0.8,0.2,0.6],
      "dims": [4,1,3], "occupancy": [1,1,1,1, 1,0,0,0, 1,0,0,0]}})"));
  ASSERT_EQ(m.num_elements(), 6);
  EXPECT_NEAR(mesh_volume(m), 6 * 0.008, 1e-12);
  // The column stands at x < 0.2 only.
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v)
    if (m.vertices(v, 2) > 0.2 + 1e-9) {
      EXPECT_LE(m.vertices(v, 0), 0.2 + 1e-9);
    }
  EXPECT_NEAR(m.vertices.col(0).maxCoeff(), 0.8, 1e-12);
}

// ---- shipped scenes

TEST(SceneFile, EveryExampleSceneLoadsAndBuilds) {
  int count = 0;
  for (const auto& dir : {examples_dir(), examples_dir() / "features"}) {
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (entry.path().extension() != ".json") continue;
      SCOPED_TRACE(entry.path().string());
      Scene s;
      ASSERT_NO_THROW(s = load_scene(entry.path())) << error_message([&] { load_scene(entry.path()); });
      // Building the paper-size stretch meshes would take a while; the small ones are built.
      if (entry.path().parent_path().filename() == "features") {
        EXPECT_FALSE(s.description.empty());
        EXPECT_GT(build_scene_mesh(s).num_elements(), 0);
      }
      ++count;
    }
  }
  EXPECT_GE(count, 20);
}

TEST(SceneFile, DocumentationShowsEveryFeatureSceneVerbatim) {
  // docs/scene-format.md reproduces each examples/features scene after a marker comment
  // "<!-- examples/features/NAME.json -->"; the two must not drift apart.
  const std::string doc = test::read_file(test::data_path("../../docs/scene-format.md"));
  ASSERT_FALSE(doc.empty());
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(examples_dir() / "features")) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    const std::string marker = "<!-- examples/features/" + entry.path().filename().string() + " -->\n```json\n";
    const auto at = doc.find(marker);
    ASSERT_NE(at, std::string::npos) << "not shown in docs/scene-format.md";
    const auto begin = at + marker.size();
    const auto end = doc.find("```", begin);
    ASSERT_NE(end, std::string::npos);
    EXPECT_EQ(json::parse(doc.substr(begin, end - begin)), json::parse(test::read_file(entry.path())));
    ++count;
  }
  EXPECT_GE(count, 20);
}

}  // namespace
}  // namespace sinew
