// Voxelising on a chosen grid (`grid_origin`): lattice planes through a given point, so rig bones
// along those planes bind rings of vertices; and the scene key's checks.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "sinew/core/error.hpp"
#include "sinew/io/surface_reader.hpp"
#include "sinew/mesh/voxelize.hpp"
#include "sinew/model/scene.hpp"

namespace sinew {
namespace {

const std::filesystem::path kExamples = SINEW_EXAMPLES;

TEST(VoxelizeGridOrigin, LatticePlanesPassThroughTheGivenPoint) {
  const TriangleSurface arm = read_triangle_surface(kExamples / "meshes" / "arm.obj");
  const InsideTest inside(arm);
  const double h = 0.02;
  VoxelizeOptions options;
  options.cell_size = h;
  const VolumeMesh plain = voxelize_surface(inside, options);
  options.grid_origin = Eigen::Vector3d(0.005, 0.0, -0.003);
  const VolumeMesh aligned = voxelize_surface(inside, options);
  auto on_grid = [&](const VolumeMesh& m) {
    for (Eigen::Index v = 0; v < m.num_vertices(); ++v)
      for (int i = 0; i < 3; ++i) {
        const double steps = (m.vertices(v, i) - (*options.grid_origin)(i)) / h;
        if (std::abs(steps - std::round(steps)) > 1e-9) return false;
      }
    return true;
  };
  EXPECT_TRUE(on_grid(aligned));
  EXPECT_FALSE(on_grid(plain));  // the bounding-box minimum is not on that grid
  // The shifted lattice still covers the whole surface.
  const Eigen::Vector3d lo = aligned.vertices.colwise().minCoeff(), hi = aligned.vertices.colwise().maxCoeff();
  EXPECT_TRUE((lo.array() <= arm.bounds().min().array()).all());
  EXPECT_TRUE((hi.array() >= arm.bounds().max().array()).all());
  options.grid_origin = Eigen::Vector3d(std::nan(""), 0, 0);
  EXPECT_THROW(voxelize_surface(inside, options), Error);
}

TEST(VoxelizeGridOrigin, SceneKeyIsCheckedAndTheElbowExampleLoads) {
  const Scene elbow = load_scene(kExamples / "elbow.json");
  ASSERT_TRUE(elbow.rig);
  ASSERT_TRUE(elbow.self_contact);
  const auto* voxels = std::get_if<SurfaceVoxels>(&elbow.mesh.source);
  ASSERT_NE(voxels, nullptr);
  ASSERT_TRUE(voxels->grid_origin.has_value());
  EXPECT_EQ(*voxels->grid_origin, Eigen::Vector3d::Zero());

  nlohmann::json box = nlohmann::json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}, "cells": [2, 2, 2], "grid_origin": [0, 0, 0]},
    "material": {"family": "stable_neo_hookean", "E": 1e4, "nu": 0.3}})");
  try {
    parse_scene(box, "box.json");
    ADD_FAILURE() << "grid_origin without a surface was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/mesh/grid_origin"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sinew
