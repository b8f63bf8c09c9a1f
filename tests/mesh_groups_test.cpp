// Gmsh physical groups as selectors: the .msh reader keeps each physical group's vertices
// (versions 2.2 and 4.1, tests/data/make_msh_groups.py), a {"group": name or tag} selector
// picks them, and a wrong group is an error that lists the mesh's groups.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "io_test_support.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/selection.hpp"
#include "sinew/model/model.hpp"

namespace sinew {
namespace {

using nlohmann::json;
using test::error_message;
using test::expect_contains;

// The vertices whose rest position passes `inside`, sorted.
template <class F>
std::vector<int> where(const VolumeMesh& m, F inside) {
  std::vector<int> out;
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v)
    if (inside(Eigen::Vector3d(m.vertices.row(v).transpose()))) out.push_back(static_cast<int>(v));
  return out;
}

const MeshGroup* find(const VolumeMesh& m, int dimension, int tag) {
  for (const MeshGroup& g : m.groups)
    if (g.dimension == dimension && g.tag == tag) return &g;
  return nullptr;
}

std::string selection_error(const VolumeMesh& m, const GroupSelector& s) {
  return error_message([&] { select_vertices(m, s, "scene.json: /boundary/0/select"); });
}

class GmshGroups : public ::testing::TestWithParam<const char*> {};

TEST_P(GmshGroups, ReaderKeepsEachPhysicalGroupsVertices) {
  const VolumeMesh m = read_volume_mesh(test::data_path(GetParam()));
  EXPECT_EQ(m.kind, std::string(GetParam()) == "groups_v22.msh" ? ElementKind::Hex8 : ElementKind::Tet4);
  ASSERT_EQ(m.num_vertices(), 12);
  ASSERT_EQ(m.groups.size(), 6u);  // the y = 0 faces have no physical group
  auto check = [&](int dimension, int tag, const std::string& name, const std::vector<int>& expected) {
    SCOPED_TRACE(name + " " + std::to_string(tag));
    const MeshGroup* g = find(m, dimension, tag);
    ASSERT_NE(g, nullptr);
    EXPECT_EQ(g->name, name);
    EXPECT_EQ(g->vertices, expected);
  };
  check(3, 1, "solid", where(m, [](auto) { return true; }));
  check(2, 1, "bottom", where(m, [](auto p) { return p.z() == 0; }));
  check(2, 2, "left", where(m, [](auto p) { return p.x() == 0; }));
  check(2, 3, "right", where(m, [](auto p) { return p.x() == 2; }));
  check(2, 7, "", where(m, [](auto p) { return p.z() == 1 && p.x() >= 1; }));
  check(2, 9, "unused", {});
}

TEST_P(GmshGroups, SelectorPicksAGroupByNameOrTag) {
  const VolumeMesh m = read_volume_mesh(test::data_path(GetParam()));
  auto select = [&](GroupSelector s) { return select_vertices(m, s, "here"); };
  EXPECT_EQ(select({"left", {}, {}}), where(m, [](auto p) { return p.x() == 0; }));
  EXPECT_EQ(select({{}, 3, {}}), where(m, [](auto p) { return p.x() == 2; }));
  EXPECT_EQ(select({{}, 7, {}}), where(m, [](auto p) { return p.z() == 1 && p.x() >= 1; }));
  EXPECT_EQ(select({{}, 1, 2}), where(m, [](auto p) { return p.z() == 0; }));
  EXPECT_EQ(select({{}, 1, 3}).size(), 12u);
  EXPECT_EQ(select({"solid", {}, 3}).size(), 12u);
}

TEST_P(GmshGroups, WrongGroupsAreNamedWithTheChoices) {
  const VolumeMesh m = read_volume_mesh(test::data_path(GetParam()));
  expect_contains(selection_error(m, {"inner", {}, {}}),
                  {"scene.json: /boundary/0/select", "no group named 'inner'", "'solid' (tag 1, volume)",
                   "'bottom' (tag 1, surface)", "'left' (tag 2, surface)", "tag 7 (surface)"});
  expect_contains(selection_error(m, {{}, 4, {}}), {"no group with tag 4", "'right' (tag 3, surface)"});
  expect_contains(selection_error(m, {"left", {}, 3}), {"no group named 'left' of dimension 3"});
  expect_contains(selection_error(m, {{}, 1, {}}),
                  {"2 groups with tag 1", "'solid' (tag 1, volume)", "'bottom' (tag 1, surface)", "\"dimension\""});
  expect_contains(selection_error(m, {"unused", {}, {}}), {"'unused' (tag 9, surface) has no vertices"});
}

INSTANTIATE_TEST_SUITE_P(Versions, GmshGroups, ::testing::Values("groups_v22.msh", "groups_v41.msh"),
                         [](const auto& p) { return std::string(p.param).substr(7, 3); });

TEST(MeshGroups, GeneratedMeshesHaveNone) {
  const VolumeMesh m = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i::Ones());
  expect_contains(selection_error(m, {"left", {}, {}}), {"no group named 'left'", "the mesh has no groups", "Gmsh"});
  // Without the mesh (rest positions only) a group cannot be resolved.
  expect_contains(error_message([&] { select_vertices(m.vertices, GroupSelector{"left", {}, {}}, "ctx"); }),
                  {"ctx", "needs the mesh's groups"});
}

TEST(MeshGroups, ReaderRejectsABadPhysicalName) {
  test::TempDir dir;
  const auto file = dir.write("bad.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 1 left\n$EndPhysicalNames\n");
  expect_contains(error_message([&] { read_volume_mesh(file); }), {"bad.msh:6", "quoted name", "left"});
}

json group_scene(const std::string& mesh_file) {
  json j = {{"mesh", {{"file", test::data_path(mesh_file).string()}}},
            {"material", {{"family", "stable_neo_hookean"}, {"E", 1e5}, {"nu", 0.3}}}};
  j["boundary"] = json::parse(R"([{"name": "wall", "select": {"group": "left"}},
                                  {"name": "floor", "select": {"group": 1, "dimension": 2}}])");
  j["loads"] = json::parse(R"({"pressure": [{"select": {"group": 3}, "pressure": 10}],
                               "point": [{"select": {"group": 7}, "force": [0, 0, -1]}]})");
  return j;
}

TEST(MeshGroups, SceneSelectsBoundaryAndLoadsByGroup) {
  for (const char* file : {"groups_v22.msh", "groups_v41.msh"}) {
    SCOPED_TRACE(file);
    const Model m = build_model(parse_scene(group_scene(file), "dir/scene.json"));
    const VolumeMesh& mesh = m.disc->mesh();
    ASSERT_EQ(m.kinematics->size(), 2u);
    EXPECT_EQ((*m.kinematics)[0].vertices, where(mesh, [](auto p) { return p.x() == 0; }));
    EXPECT_EQ((*m.kinematics)[1].vertices, where(mesh, [](auto p) { return p.z() == 0; }));
    ASSERT_EQ(m.pressures.size(), 1u);
    EXPECT_EQ(m.pressures[0]->faces().size(), mesh.kind == ElementKind::Hex8 ? 1u : 2u);
    EXPECT_NEAR(m.external_forces.sum(), -4.0, 1e-12);  // 4 vertices of group 7
  }
}

TEST(MeshGroups, SceneErrorsNameThePath) {
  json j = group_scene("groups_v22.msh");
  j["boundary"][0]["select"] = {{"group", "nope"}};
  expect_contains(error_message([&] { build_model(parse_scene(j, "dir/scene.json")); }),
                  {"dir/scene.json: /boundary/0/select", "no group named 'nope'", "'left' (tag 2, surface)"});
  j["boundary"][0]["select"] = {{"group", json::array()}};
  expect_contains(error_message([&] { parse_scene(j, "dir/scene.json"); }), {"/boundary/0/select/group", "name", "tag"});
  j["boundary"][0]["select"] = {{"plane", {{"point", {0, 0, 0}}, {"normal", {1, 0, 0}}}}, {"dimension", 2}};
  expect_contains(error_message([&] { parse_scene(j, "dir/scene.json"); }), {"/boundary/0/select/dimension", "only with group"});
  j["boundary"][0]["select"] = {{"group", 2}, {"dimension", 4}};
  expect_contains(error_message([&] { parse_scene(j, "dir/scene.json"); }), {"/boundary/0/select/dimension"});
}

}  // namespace
}  // namespace sinew
