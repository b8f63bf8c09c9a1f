// The browser viewer's files: the GLB (read back here byte by byte: header, chunks, accessors,
// morph targets that reproduce every frame, the STEP animation, field arrays), the HTML page
// (the same GLB inline, the script inline and unable to close its element), and the scene
// adapter's fields (J and von Mises) on a real run.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <numbers>

#include "io_test_support.hpp"
#include "sinew/io/base64.hpp"
#include "sinew/io/gltf_writer.hpp"
#include "sinew/io/viewer_writer.hpp"
#include "sinew/element/nodal_fields.hpp"
#include "sinew/run/run_viewer.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {
namespace {

using nlohmann::json;
using test::error_message;
using test::expect_contains;
using test::TempDir;

std::uint32_t u32_at(const std::string& s, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}

// A GLB split into its JSON and BIN chunks, with typed reads of accessors.
struct Glb {
  json gltf;
  std::string bin;

  explicit Glb(const std::string& bytes) {
    EXPECT_EQ(u32_at(bytes, 0), 0x46546C67u);  // "glTF"
    EXPECT_EQ(u32_at(bytes, 4), 2u);
    EXPECT_EQ(u32_at(bytes, 8), bytes.size());
    const std::uint32_t json_length = u32_at(bytes, 12);
    EXPECT_EQ(u32_at(bytes, 16), 0x4E4F534Au);
    EXPECT_EQ(json_length % 4, 0u);
    gltf = json::parse(bytes.substr(20, json_length));
    const std::size_t bin_at = 20 + json_length;
    EXPECT_EQ(u32_at(bytes, bin_at + 4), 0x004E4942u);
    bin = bytes.substr(bin_at + 8, u32_at(bytes, bin_at));
    EXPECT_EQ(bin.size(), gltf["buffers"][0]["byteLength"].get<std::size_t>());
  }

  template <class T>
  std::vector<T> read(int accessor) const {
    const json& a = gltf["accessors"][accessor];
    const json& view = gltf["bufferViews"][a["bufferView"].get<int>()];
    const std::size_t components = a["type"] == "VEC3" ? 3 : 1;
    const std::size_t count = a["count"].get<std::size_t>() * components;
    EXPECT_EQ(view["byteLength"].get<std::size_t>(), count * sizeof(T));
    EXPECT_EQ(view["byteOffset"].get<std::size_t>() % 4, 0u);
    std::vector<T> out(count);
    std::memcpy(out.data(), bin.data() + view["byteOffset"].get<std::size_t>(), count * sizeof(T));
    return out;
  }
};

// Two triangles (a unit square) moving in three frames, with one field, and a static square.
AnimatedScene square_scene() {
  AnimatedScene s;
  s.frame_numbers = {0, 5, 10};
  s.times = {0.0, 0.5, 1.0};
  AnimatedMesh m;
  m.name = "body";
  m.role = "body";
  m.triangles.resize(2, 3);
  m.triangles << 0, 1, 2, 0, 2, 3;
  Eigen::MatrixX3f p(4, 3);
  p << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  m.field_names = {"J"};
  for (int f = 0; f < 3; ++f) {
    Eigen::MatrixX3f q = p;
    q.col(0) *= 1.0f + 0.5f * f;  // stretched along x
    q.col(2).array() += 0.25f * f;
    m.positions.push_back(q);
    m.fields.push_back({Eigen::VectorXf::Constant(4, 1.0f + 0.5f * f)});
  }
  s.meshes.push_back(m);
  AnimatedMesh still = m;
  still.name = "ground";
  still.role = "obstacle";
  still.field_names.clear();
  still.fields.clear();
  still.positions.assign(3, p);
  still.color.w() = 0.5f;
  s.meshes.push_back(still);
  return s;
}

TEST(GltfWriter, MorphTargetsReproduceEveryFrame) {
  const AnimatedScene s = square_scene();
  const Glb glb(glb_bytes(s));
  const json& g = glb.gltf;
  EXPECT_EQ(g["asset"]["version"], "2.0");
  ASSERT_EQ(g["meshes"].size(), 2u);
  const json& prim = g["meshes"][0]["primitives"][0];
  const auto base = glb.read<float>(prim["attributes"]["POSITION"].get<int>());
  ASSERT_EQ(prim["targets"].size(), 2u);  // frames 1 and 2
  for (int f = 0; f < 3; ++f) {
    std::vector<float> p = base;
    if (f > 0) {
      const auto delta = glb.read<float>(prim["targets"][f - 1]["POSITION"].get<int>());
      for (std::size_t i = 0; i < p.size(); ++i) p[i] += delta[i];
    }
    for (int v = 0; v < 4; ++v)
      for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(p[3 * v + k], s.meshes[0].positions[f](v, k)) << f << " " << v;
  }
  const auto indices = glb.read<std::uint32_t>(prim["indices"].get<int>());
  EXPECT_EQ(indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
  // POSITION accessors carry bounds (required by glTF).
  EXPECT_EQ(g["accessors"][prim["attributes"]["POSITION"].get<int>()]["max"], json({1.0, 1.0, 0.0}));

  // One STEP channel for the moving mesh: at time t_f the weights are e_f.
  ASSERT_EQ(g["animations"].size(), 1u);
  const json& anim = g["animations"][0];
  ASSERT_EQ(anim["channels"].size(), 1u);
  EXPECT_EQ(anim["channels"][0]["target"]["path"], "weights");
  EXPECT_EQ(g["nodes"][anim["channels"][0]["target"]["node"].get<int>()]["name"], "body");
  const json& sampler = anim["samplers"][0];
  EXPECT_EQ(sampler["interpolation"], "STEP");
  EXPECT_EQ(glb.read<float>(sampler["input"].get<int>()), (std::vector<float>{0.0f, 0.5f, 1.0f}));
  EXPECT_EQ(glb.read<float>(sampler["output"].get<int>()), (std::vector<float>{0, 0, 1, 0, 0, 1}));

  // Fields per frame under extras, with their range; COLOR_0 from frame 0.
  const json& extras = g["meshes"][0]["extras"];
  ASSERT_EQ(extras["fields"]["J"].size(), 3u);
  EXPECT_EQ(glb.read<float>(extras["fields"]["J"][2].get<int>()), std::vector<float>(4, 2.0f));
  EXPECT_EQ(extras["field_ranges"]["J"], json({1.0, 2.0}));
  EXPECT_TRUE(prim["attributes"].contains("COLOR_0"));
  EXPECT_EQ(g["extras"]["sinew"]["frames"], json({0, 5, 10}));

  // Under a field the base colour is white (COLOR_0 multiplies it); the own colour is in extras.
  EXPECT_EQ(g["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"], json({1.0, 1.0, 1.0, 1.0}));
  EXPECT_NEAR(extras["base_color"][0].get<double>(), 0.8, 1e-6);
  // The static obstacle: no targets, blended material, no animation channel.
  EXPECT_FALSE(g["meshes"][1]["primitives"][0].contains("targets"));
  EXPECT_EQ(g["materials"][1]["alphaMode"], "BLEND");
  // z-up: a root node turns +z into +y.
  EXPECT_NEAR(g["nodes"][0]["rotation"][0].get<double>(), -std::sqrt(0.5), 1e-12);
  EXPECT_EQ(g["nodes"][0]["children"], json({1, 2}));
}

TEST(GltfWriter, RejectsInconsistentScenes) {
  AnimatedScene s = square_scene();
  s.times = {0.0, 0.5, 0.5};
  expect_contains(error_message([&] { glb_bytes(s); }), {"time of frame 2", "does not increase"});
  s = square_scene();
  s.meshes[0].positions[1].conservativeResize(3, 3);
  expect_contains(error_message([&] { glb_bytes(s); }), {"glTF mesh 'body'", "frame 1 has 3 vertices"});
  s = square_scene();
  s.meshes[0].triangles(1, 2) = 7;
  expect_contains(error_message([&] { glb_bytes(s); }), {"'body'", "outside 0..3"});
  s = square_scene();
  s.meshes[0].fields[2][0](1) = std::nanf("");
  expect_contains(error_message([&] { glb_bytes(s); }), {"field 'J' of frame 2", "non-finite"});
  s = square_scene();
  s.meshes[1].positions.pop_back();
  expect_contains(error_message([&] { glb_bytes(s); }), {"'ground'", "2 frames of positions"});
}

std::vector<ViewerObject> square_objects() {
  Eigen::MatrixX3i t(2, 3);
  t << 0, 1, 2, 0, 2, 3;
  return {{"body", ViewerRole::Body, t, {"J"}}, {"ball", ViewerRole::Obstacle, t, {}}};
}

std::vector<ViewerObjectFrame> square_frame(double s) {
  Eigen::MatrixX3d p(4, 3);
  p << 0, 0, 0, s, 0, 0, s, 1, 0, 0, 1, 0;
  return {{p, {Eigen::VectorXd::Constant(4, s)}}, {p, {}}};
}

TEST(ViewerWriter, PageCarriesTheGlbAndTheScript) {
  TempDir dir;
  const auto script = dir.write("viewer.js", "console.log('</script><b>');");
  ViewerOptions options;
  options.script = script;
  options.title = "a <run>";
  ViewerWriter w(square_objects(), options);
  w.add_frame(0, 0.0, square_frame(1.0));
  w.add_frame(1, 1.0, square_frame(1.5));
  w.finish(dir / "viewer.html");
  const std::string glb = test::read_file(dir / "viewer.glb");
  EXPECT_EQ(glb, glb_bytes(w.scene()));
  const std::string html = test::read_file(dir / "viewer.html");
  const std::string open = "<script type=\"application/octet-stream\" id=\"sinew-glb\">";
  const std::size_t at = html.find(open) + open.size();
  const std::size_t end = html.find("</script>", at);
  const auto decoded = base64_decode(std::string_view(html).substr(at, end - at));
  EXPECT_EQ(std::string(decoded.begin(), decoded.end()), glb);
  expect_contains(html, {"<title>a &lt;run&gt;</title>", "console.log('<\\/script><b>');", "\"fps\":12"});
  EXPECT_EQ(html.find("</script><b>"), std::string::npos);
}

TEST(ViewerWriter, RejectsBadFramesAndAMissingScript) {
  ViewerWriter w(square_objects());
  w.add_frame(0, 0.0, square_frame(1.0));
  auto bad = square_frame(1.5);
  bad[0].fields[0].resize(3);
  expect_contains(error_message([&] { w.add_frame(1, 1.0, bad); }),
                  {"viewer object 'body', frame 1", "field 'J' has 3 values for 4 vertices"});
  expect_contains(error_message([&] { w.add_frame(1, 0.0, square_frame(1.5)); }), {"frame 1 has time 0", "not after"});
  bad = square_frame(1.5);
  bad[1].positions.conservativeResize(5, 3);
  bad[1].positions.row(4).setZero();
  expect_contains(error_message([&] { w.add_frame(1, 1.0, bad); }), {"'ball'", "5 vertices, earlier frames have 4"});
  EXPECT_EQ(w.frames(), 1u);  // the rejected frames left nothing behind

  expect_contains(error_message([] { ViewerWriter({}); }), {"no objects"});
  auto twice = square_objects();
  twice[1].name = "body";
  expect_contains(error_message([&] { ViewerWriter{twice}; }), {"two objects are named 'body'"});

  TempDir dir;
  ViewerOptions options;
  options.script = dir / "missing.js";
  ViewerWriter v(square_objects(), options);
  v.add_frame(0, 0.0, square_frame(1.0));
  expect_contains(error_message([&] { v.finish(dir / "viewer.html"); }), {"missing.js", "viewer script"});
  EXPECT_TRUE(dir.entries().empty());
}

// A 1 x 0.5 x 0.5 box of 4 x 2 x 2 hexes with a sphere obstacle and a capsule bone.
Scene small_scene(const TempDir& dir) {
  const json j = json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.5, 0.5]}, "cells": [4, 2, 2]},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.3},
    "boundary": [
      {"name": "left", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}},
      {"name": "right", "select": {"plane": {"point": [1, 0, 0], "normal": [1, 0, 0]}},
       "motion": {"type": "translate", "per_frame": [0.1, 0, 0]}}
    ],
    "obstacles": [{"name": "ball", "type": "sphere", "center": [0.5, 0.25, 2], "radius": 0.2, "stiffness": 1e8,
                   "motion": {"type": "translate", "per_frame": [0, 0, -0.1]}}],
    "frames": 2
  })");
  // On disk: a run's checkpoint fingerprints the scene file.
  return load_scene(dir.write("scene.json", j.dump()));
}

TEST(RunViewer, FieldsAreJAndVonMisesOfTheDeformation) {
  TempDir dir;
  const Scene scene = small_scene(dir);
  auto disc = std::make_shared<const Discretization>(build_scene_mesh(scene));
  auto material = build_material(scene.material);
  // A uniform stretch F = diag(1.2, 0.9, 0.9): J = 0.972 everywhere, sigma uniaxial-like.
  const Eigen::Vector3d stretch(1.2, 0.9, 0.9);
  Eigen::VectorXd x = disc->mesh().rest_positions();
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) *= stretch(i % 3);
  const ElementStressFields f = element_stress_fields(*disc, *material, x);
  const Mat3 F = stretch.asDiagonal();
  const Mat3 sigma = material->pk1(F) * F.transpose() / F.determinant();
  const double expected_vm = std::abs(sigma(0, 0) - sigma(1, 1));  // sigma_yy = sigma_zz, no shear
  EXPECT_GT(expected_vm, 1e3);
  for (Eigen::Index e = 0; e < f.J.size(); ++e) {
    EXPECT_NEAR(f.J(e), 0.972, 1e-12);
    EXPECT_NEAR(f.von_mises(e), expected_vm, 1e-9 * expected_vm);
  }
  const Eigen::VectorXd at_rest = element_stress_fields(*disc, *material, disc->mesh().rest_positions()).von_mises;
  EXPECT_LT(at_rest.cwiseAbs().maxCoeff(), 1e-6);
  // Vertex averages of a constant are that constant; a non-finite element is skipped.
  Eigen::VectorXd values = Eigen::VectorXd::Constant(disc->num_elements(), 2.5);
  values(0) = std::nan("");
  const Eigen::VectorXd v = nodal_average(*disc, values);
  EXPECT_TRUE(v.allFinite());
  EXPECT_NEAR(v.minCoeff(), 0.0, 0.0);  // vertex 0 belongs to element 0 only
  EXPECT_NEAR(v.maxCoeff(), 2.5, 1e-12);
}

TEST(RunViewer, ViewerOfARunFromItsOutputFolder) {
  TempDir dir;
  const Scene scene = small_scene(dir);
  RunOptions options;
  options.out_dir = dir / "out";
  run_scene(scene, options);
  const auto frames = read_run_frames(options.out_dir, 5 * 3 * 3);
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[2].frame, 2);
  // The right end moved to x = 1 + 2 x 0.1; the left end stayed at 0.
  const auto xs = frames[2].x.reshaped(3, 45).row(0);
  EXPECT_NEAR(xs.maxCoeff(), 1.2, 1e-12);
  EXPECT_NEAR(xs.minCoeff(), 0.0, 1e-12);
  EXPECT_NEAR(frames[1].time, 1.0, 0.0);  // quasistatic: the frame number

  ViewerOptions vo;
  vo.script = dir.write("viewer.js", "/* test */");
  EXPECT_EQ(write_run_viewer(scene, options.out_dir, vo), 3u);
  const Glb glb(test::read_file(options.out_dir / "viewer.glb"));
  ASSERT_EQ(glb.gltf["meshes"].size(), 2u);
  EXPECT_EQ(glb.gltf["meshes"][1]["name"], "obstacle ball");
  EXPECT_EQ(glb.gltf["meshes"][1]["extras"]["role"], "obstacle");
  // The ball moves down 0.1 per frame: its frame-2 morph target is (0, 0, -0.2) everywhere.
  const auto delta = glb.read<float>(glb.gltf["meshes"][1]["primitives"][0]["targets"][1]["POSITION"].get<int>());
  for (std::size_t i = 0; i < delta.size(); ++i) EXPECT_NEAR(delta[i], i % 3 == 2 ? -0.2 : 0.0, 1e-6);
  // The body's J at frame 0 is 1 and below/above 1 later; von Mises at rest is 0.
  const json& fields = glb.gltf["meshes"][0]["extras"]["fields"];
  for (float J : glb.read<float>(fields["J"][0].get<int>())) EXPECT_NEAR(J, 1.0f, 1e-6f);
  for (float s : glb.read<float>(fields["von_mises"][0].get<int>())) EXPECT_NEAR(s, 0.0f, 1e-3f);
  float max_vm = 0.0f;
  for (float s : glb.read<float>(fields["von_mises"][2].get<int>())) max_vm = std::max(max_vm, s);
  EXPECT_GT(max_vm, 1e3f);

  expect_contains(error_message([&] { read_run_frames(dir.path(), 45); }), {"simulation.pvd", "vtu"});
  expect_contains(error_message([&] { read_run_frames(options.out_dir, 44); }), {"frame_0000.vtu", "45 vertices", "has 44"});
}

}  // namespace
}  // namespace sinew
