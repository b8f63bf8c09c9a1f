// Obstacle and bone surfaces for output: closed, outward and close to the analytic volume;
// moved by the obstacle's path and the bone's keys; file stems safe and unique.
#include <gtest/gtest.h>

#include <numbers>

#include "sinew/contact/obstacle.hpp"
#include "sinew/mesh/shape_surfaces.hpp"
#include "sinew/rig/bone_surface.hpp"
#include "sinew/scene/shape_output.hpp"

namespace sinew {
namespace {

constexpr double pi = std::numbers::pi;

TEST(ShapeSurfaces, ClosedOutwardAndNearTheAnalyticVolume) {
  const Eigen::Vector3d c(0.3, -0.2, 1.0);
  const TriangleSurface sphere = sphere_surface(c, 0.5, 48);
  EXPECT_NO_THROW(sphere.validate("sphere"));
  EXPECT_NEAR(sphere.volume(), 4.0 / 3.0 * pi * 0.125, 0.02 * 4.0 / 3.0 * pi * 0.125);
  EXPECT_LT(((sphere.vertices.rowwise() - c.transpose()).rowwise().norm().array() - 0.5).abs().maxCoeff(), 1e-12);

  const TriangleSurface capsule = capsule_surface(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 0), 0.2, 48);
  EXPECT_NO_THROW(capsule.validate("capsule"));
  const double capsule_volume = pi * 0.04 * std::sqrt(2.0) + 4.0 / 3.0 * pi * 0.008;
  EXPECT_NEAR(capsule.volume(), capsule_volume, 0.02 * capsule_volume);

  const TriangleSurface cylinder = cylinder_surface(c, Eigen::Vector3d(0, 0, 3), 0.1, 1.2, 64);
  EXPECT_NO_THROW(cylinder.validate("cylinder"));
  EXPECT_NEAR(cylinder.volume(), pi * 0.01 * 1.2, 0.01 * pi * 0.01 * 1.2);
  EXPECT_NEAR(cylinder.bounds().max().z() - cylinder.bounds().min().z(), 1.2, 1e-12);

  const TriangleSurface box = box_surface(Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(1, 0.5, 3));
  EXPECT_NO_THROW(box.validate("box"));
  EXPECT_NEAR(box.volume(), 2 * 0.5 * 3, 1e-12);

  const TriangleSurface square = square_surface(Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(0, 0, 5), 1.5);
  EXPECT_EQ(square.num_faces(), 2);
  const Eigen::Vector3d a = square.vertices.row(square.faces(0, 0)), b = square.vertices.row(square.faces(0, 1)),
                        d = square.vertices.row(square.faces(0, 2));
  EXPECT_GT((b - a).cross(d - a).z(), 0.0);  // faces the normal
  EXPECT_NEAR((square.vertices.col(2).array() - 2.0).abs().maxCoeff(), 0.0, 1e-15);
  EXPECT_NEAR(square.vertices.col(0).maxCoeff() - square.vertices.col(0).minCoeff(), 3.0, 1e-12);
}

TEST(ShapeSurfaces, ObstaclesMoveAlongTheirPath) {
  const Obstacle still("ball", std::make_shared<SphereObstacle>(Eigen::Vector3d(0, 0, 0), 0.5));
  const Obstacle moving("ball", std::make_shared<SphereObstacle>(Eigen::Vector3d(0, 0, 0), 0.5),
                        Translation{Eigen::Vector3d(0.1, 0, 0)});
  const TriangleSurface s0 = still.surface_at(3.0, 1.0), s3 = moving.surface_at(3.0, 1.0);
  EXPECT_LT(((s3.vertices - s0.vertices).rowwise() - Eigen::RowVector3d(0.3, 0, 0)).cwiseAbs().maxCoeff(), 1e-12);
  const Obstacle ground("ground", std::make_shared<PlaneObstacle>(Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0, 0, 1)));
  const TriangleSurface g = ground.surface_at(0.0, 4.0);
  EXPECT_NEAR(g.vertices.col(0).maxCoeff(), 4.0, 1e-12);
  EXPECT_NEAR(g.vertices.col(2).maxCoeff(), -1.0, 1e-12);
}

TEST(ShapeSurfaces, BonesFollowTheirKeys) {
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
}

TEST(ShapeSurfaces, FileStemsAreSafeAndUnique) {
  EXPECT_EQ(shape_file_stems("obstacle_", {"press", "left wall", "left/wall", ""}),
            (std::vector<std::string>{"obstacle_press", "obstacle_left_wall", "obstacle_left_wall_2", "obstacle_3"}));
}

}  // namespace
}  // namespace sinew
