// Mesh bones: a closed triangle surface as a bone's rest shape (rig files `"mesh": "bone.obj"`).
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io_test_support.hpp"
#include "sinew/core/error.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/model/rig_reader.hpp"

namespace sinew {
namespace {

using test::TempDir;

// An OBJ of a capsule along x from a to b: `around` segments round the axis, `rings` latitude
// steps per hemispherical cap, all vertices on the exact capsule. Faces wind outwards.
// Leaving out the last face makes the surface open.
std::string capsule_obj(double ax, double bx, double r, int around, int rings, bool open = false) {
  std::ostringstream out;
  // Profile from the -x pole to the +x pole: (x, radius) pairs.
  std::vector<std::pair<double, double>> profile;
  for (int i = 1; i <= rings; ++i) {
    const double t = std::numbers::pi / 2 * i / rings;  // from the pole to the equator
    profile.emplace_back(ax - r * std::cos(t), r * std::sin(t));
  }
  for (int i = rings; i >= 1; --i) {
    const double t = std::numbers::pi / 2 * i / rings;
    profile.emplace_back(bx + r * std::cos(t), r * std::sin(t));
  }
  out << fmt::format("v {} 0 0\n", ax - r);
  for (const auto& [x, rad] : profile)
    for (int k = 0; k < around; ++k) {
      const double phi = 2 * std::numbers::pi * k / around;
      out << fmt::format("v {} {} {}\n", x, rad * std::cos(phi), rad * std::sin(phi));
    }
  out << fmt::format("v {} 0 0\n", bx + r);
  const int n_rings = static_cast<int>(profile.size());
  auto id = [&](int ring, int k) { return 2 + ring * around + (k % around); };  // 1-based OBJ
  const int last = 2 + n_rings * around;
  std::vector<std::array<int, 3>> faces;
  for (int k = 0; k < around; ++k) faces.push_back({1, id(0, k + 1), id(0, k)});
  for (int ring = 0; ring + 1 < n_rings; ++ring)
    for (int k = 0; k < around; ++k) {
      faces.push_back({id(ring, k), id(ring, k + 1), id(ring + 1, k + 1)});
      faces.push_back({id(ring, k), id(ring + 1, k + 1), id(ring + 1, k)});
    }
  for (int k = 0; k < around; ++k) faces.push_back({last, id(n_rings - 1, k), id(n_rings - 1, k + 1)});
  if (open) faces.pop_back();
  for (const auto& f : faces) out << fmt::format("f {} {} {}\n", f[0], f[1], f[2]);
  return out.str();
}

nlohmann::json rig_with(const nlohmann::json& shape_key, const nlohmann::json& shape) {
  nlohmann::json bone = {{"name", "bone"}, {"keys", {{{"frame", 0}}}}};
  bone[shape_key.get<std::string>()] = shape;
  return {{"bones", {bone}}};
}

TEST(MeshBone, CapturesTheSameLatticeVerticesAsTheEquivalentCapsule) {
  TempDir dir;
  const double r = 0.3;
  dir.write("capsule.obj", capsule_obj(-0.5, 0.5, r, 48, 12));
  // Relative to the rig file's folder.
  const auto rig_file = dir.write("rig.json", rig_with("mesh", "capsule.obj").dump());
  const Rig mesh_rig = load_rig(rig_file);
  ASSERT_EQ(mesh_rig.bones[0].shape->kind(), "mesh");
  const Rig capsule_rig =
      parse_rig(rig_with("capsule", {{"a", {-0.5, 0, 0}}, {"b", {0.5, 0, 0}}, {"radius", r}}), dir / "inline.json");

  const VolumeMesh lattice = box_lattice({-1, -0.5, -0.5}, {1, 0.5, 0.5}, {40, 20, 20});
  const RigBinding by_mesh = bind_rig(mesh_rig, lattice.vertices);
  const RigBinding by_capsule = bind_rig(capsule_rig, lattice.vertices);
  ASSERT_GT(by_capsule.bound_vertices.size(), 500u);
  // The polyhedron is inscribed in the capsule: it can only lose vertices, and only those in
  // the thin shell between its facets and the round surface (chord sagitta r (1 - cos(pi/48))).
  const CapsuleShape capsule({-0.5, 0, 0}, {0.5, 0, 0}, r);
  int lost = 0;
  for (Eigen::Index v = 0; v < lattice.vertices.rows(); ++v) {
    const Eigen::Vector3d p = lattice.vertices.row(v).transpose();
    const bool in_mesh = by_mesh.bone[v] == 0, in_capsule = by_capsule.bone[v] == 0;
    // (Up to rounding on the shared surface points, e.g. the poles.)
    EXPECT_FALSE(in_mesh && capsule.distance_to_axis(p) > r + 1e-9) << p.transpose();
    if (in_capsule && !in_mesh) {
      ++lost;
      EXPECT_GT(capsule.distance_to_axis(p), 0.98 * r) << p.transpose();
    }
  }
  EXPECT_LE(lost, static_cast<int>(by_capsule.bound_vertices.size()) / 20);
}

TEST(MeshBone, OpenOrMissingMeshIsRejectedNamingTheFile) {
  TempDir dir;
  dir.write("open.obj", capsule_obj(-0.5, 0.5, 0.3, 12, 3, /*open=*/true));
  const auto rig_file = dir.write("rig.json", rig_with("mesh", "open.obj").dump());
  try {
    load_rig(rig_file);
    ADD_FAILURE() << "an open bone mesh was accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("open.obj"), std::string::npos) << what;
    EXPECT_NE(what.find("/bones/0/mesh"), std::string::npos) << what;
  }
  const auto missing = dir.write("missing.json", rig_with("mesh", "nowhere.obj").dump());
  EXPECT_THROW(load_rig(missing), Error);
  // Both shapes, or neither, is an error too.
  nlohmann::json both = rig_with("mesh", "open.obj");
  both["bones"][0]["capsule"] = {{"a", {0, 0, 0}}, {"b", {1, 0, 0}}, {"radius", 0.1}};
  EXPECT_THROW(parse_rig(both, dir / "rig.json"), Error);
}

}  // namespace
}  // namespace sinew
