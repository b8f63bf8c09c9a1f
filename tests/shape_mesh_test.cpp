// Obstacle and bone surfaces for output and display: closed, outward and close to the analytic
// volume; moved by the obstacle's path and the bone's keys; file stems safe and unique.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sinew/core/error.hpp"
#include "sinew/mesh/shape_mesh.hpp"
#include "sinew/mesh/surface.hpp"
#include "sinew/motion/bone_surface.hpp"
#include "sinew/motion/obstacle.hpp"
#include "sinew/run/shape_output.hpp"

namespace sinew {
namespace {

constexpr double pi = std::numbers::pi;

TEST(ShapeMesh, ClosedOutwardMeshesOfTheRightVolume) {
  struct Case {
    const char* name;
    TriangleSurface mesh;
    double volume;
  };
  const Eigen::Vector3d c(0.5, -1, 2), a(0, 0, 0), b(1, 2, 0.5);
  const double len = (b - a).norm();
  const std::vector<Case> cases = {
      {"sphere", sphere_mesh(c, 0.7, 48), 4.0 / 3.0 * pi * std::pow(0.7, 3)},
      {"capsule", capsule_mesh(a, b, 0.3, 48), pi * 0.09 * len + 4.0 / 3.0 * pi * 0.027},
      {"cylinder", cylinder_mesh(c, Eigen::Vector3d(1, 1, 0), 0.4, 1.5, 48), pi * 0.16 * 1.5},
      {"box", box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3)), 6.0},
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.name);
    EXPECT_NO_THROW(k.mesh.validate(k.name));  // closed, consistently oriented, positive volume
    EXPECT_TRUE(surface_topology(k.mesh).watertight());
    EXPECT_NEAR(k.mesh.volume(), k.volume, 0.01 * k.volume);
  }
  const TriangleSurface sphere = sphere_mesh(c, 0.7, 48);
  EXPECT_LT(((sphere.vertices.rowwise() - c.transpose()).rowwise().norm().array() - 0.7).abs().maxCoeff(), 1e-12);
  const TriangleSurface along_z = cylinder_mesh(c, Eigen::Vector3d(0, 0, 3), 0.1, 1.2, 32);
  EXPECT_NEAR(along_z.bounds().max().z() - along_z.bounds().min().z(), 1.2, 1e-12);

  const TriangleSurface sq = square_mesh(Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, 2), 3.0);
  EXPECT_EQ(sq.num_faces(), 2);
  const Eigen::Vector3d n = (sq.vertices.row(1) - sq.vertices.row(0)).cross(sq.vertices.row(2) - sq.vertices.row(0)).transpose();
  EXPECT_GT(n.z(), 0.0);  // faces the normal
  EXPECT_NEAR(n.norm(), 36.0, 1e-12);
  EXPECT_NEAR((sq.vertices.col(2).array() - 1.0).abs().maxCoeff(), 0.0, 1e-15);
}

TEST(ShapeMesh, ObstaclesMoveAlongTheirPath) {
  const Eigen::AlignedBox3d body(Eigen::Vector3d(1, 2, 0), Eigen::Vector3d(3, 3, 1));
  const Obstacle still("ball", std::make_shared<SphereObstacle>(Eigen::Vector3d(0, 0, 0), 0.5));
  const Obstacle moving("ball", std::make_shared<SphereObstacle>(Eigen::Vector3d(0, 0, 0), 0.5),
                        Translation{Eigen::Vector3d(0.1, 0, 0)});
  const TriangleSurface s0 = still.surface_at(3.0, body), s3 = moving.surface_at(3.0, body);
  EXPECT_LT(((s3.vertices - s0.vertices).rowwise() - Eigen::RowVector3d(0.3, 0, 0)).cwiseAbs().maxCoeff(), 1e-12);
  // The ground is a square under the body's centre (2, 2.5), three body sizes (2) wide.
  const Obstacle ground("ground", std::make_shared<PlaneObstacle>(Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0, 0, 1)));
  const TriangleSurface g = ground.surface_at(0.0, body);
  EXPECT_NEAR(g.vertices.col(0).maxCoeff(), 2.0 + 3.0, 1e-12);
  EXPECT_NEAR(g.vertices.col(1).minCoeff(), 2.5 - 3.0, 1e-12);
  EXPECT_NEAR((g.vertices.col(2).array() + 1.0).abs().maxCoeff(), 0.0, 1e-12);
}

TEST(ShapeMesh, BonesFollowTheirKeys) {
  Bone bone;
  bone.name = "forearm";
  bone.shape = std::make_shared<CapsuleShape>(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), 0.1);
  BoneKey k0, k1;
  k1.frame = 10.0;
  k1.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(pi / 2, Eigen::Vector3d::UnitZ()));
  bone.keys = {k0, k1};
  const TriangleSurface rest = bone_surface_at(bone, 0.0), turned = bone_surface_at(bone, 10.0);
  EXPECT_NEAR(rest.bounds().max().x(), 1.1, 1e-12);
  EXPECT_NEAR(turned.bounds().max().y(), 1.1, 1e-9);  // turned a quarter about z through the origin
  EXPECT_NEAR(turned.bounds().max().x(), 0.1, 1e-9);
  Bone shapeless;
  shapeless.name = "ghost";
  try {
    bone_surface_at(shapeless, 0.0);
    ADD_FAILURE() << "a bone without a shape has no surface";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ghost"), std::string::npos) << e.what();
  }
}

TEST(ShapeMesh, FileStemsAreSafeAndUnique) {
  EXPECT_EQ(shape_file_stems("obstacle_", {"press", "left wall", "left/wall", ""}),
            (std::vector<std::string>{"obstacle_press", "obstacle_left_wall", "obstacle_left_wall_2", "obstacle_3"}));
}

}  // namespace
}  // namespace sinew
