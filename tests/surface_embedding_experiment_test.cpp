// Experiment "surface embedding" (issue 5): the example torus voxelised at three resolutions,
// one side pinned, sagging under gravity. The deformed render surface written every frame must
// stay watertight with the input's connectivity, and each of its vertices must be the
// interpolation of its element's deformed nodes. Prints volume and timing per resolution.
#include <gtest/gtest.h>

#include <chrono>
#include <fmt/format.h>

#include "io_test_support.hpp"
#include "sinew/element/embedding.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/io/surface_reader.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {
namespace {

using test::TempDir;

TEST(SurfaceEmbeddingExperiment, DeformedSurfaceStaysWatertightAndFollowsTheLattice) {
  TempDir dir;
  const std::filesystem::path torus_file = std::filesystem::path(SINEW_EXAMPLES) / "meshes" / "torus.obj";
  const TriangleSurface torus = read_triangle_surface(torus_file);
  std::printf("  torus: %ld vertices, %ld faces, enclosed volume %.5f\n", static_cast<long>(torus.num_vertices()),
              static_cast<long>(torus.num_faces()), torus.volume());
  std::printf("  %10s %6s %8s %12s %14s %12s %9s\n", "resolution", "hexes", "vertices", "lattice vol", "deformed surf",
              "max sag", "seconds");
  double previous_sag = 0.0;
  for (int resolution : {6, 10, 16}) {
    const std::string name = fmt::format("r{}", resolution);
    const std::string scene = fmt::format(R"({{
      "mesh": {{"surface": "{}", "resolution": {}, "embed": true}},
      "material": {{"family": "stable_neo_hookean", "E": 1e6, "nu": 0.3}},
      "density": 1000, "loads": {{"gravity": [0, 0, -9.81]}},
      "boundary": [{{"name": "pinned", "select": {{"box": {{"min": [-1, -1, -1], "max": [0.2, 2, 2]}}}}}}],
      "solver": {{"newton": {{"convergence": "absolute", "tolerance": 1e-8}}}},
      "frames": 1
    }})", torus_file.string(), resolution);
    RunOptions options;
    options.out_dir = dir / name;
    const auto t0 = std::chrono::steady_clock::now();
    const RunSummary summary = run_scene(load_scene(dir.write(name + ".json", scene)), options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_TRUE(summary.all_converged());

    const VolumeMesh rest = read_volume_mesh(dir / name / "frame_0000.vtu");
    const VolumeMesh deformed = read_volume_mesh(dir / name / "frame_0001.vtu");
    const Embedding embedding = embed_points(rest, torus.vertices);
    EXPECT_LT(embedding.max_outside, 1e-12);
    for (const char* ext : {"obj", "ply"}) {
      const auto file = dir / name / fmt::format("embedded_surface_0001.{}", ext);
      // The reader validates closure, orientation and positive volume.
      const TriangleSurface out = read_triangle_surface(file);
      EXPECT_EQ(out.faces, torus.faces) << file;
      EXPECT_TRUE(surface_topology(out).watertight()) << file;
      // Every vertex is its element's interpolation (the text round-trips doubles exactly).
      const Eigen::MatrixX3d expected = embedding.positions(deformed.rest_positions());
      EXPECT_LT((out.vertices - expected).cwiseAbs().maxCoeff(), 1e-12) << file;
      // Rest frame: the input surface itself.
      const TriangleSurface at_rest = read_triangle_surface(dir / name / fmt::format("embedded_surface_0000.{}", ext));
      EXPECT_LT((at_rest.vertices - torus.vertices).cwiseAbs().maxCoeff(), 1e-12);
      if (std::string(ext) == "obj") {
        // Surface vertices in the pinned cells stay; the far side sags.
        double sag = 0.0, pinned_motion = 0.0;
        for (Eigen::Index v = 0; v < torus.num_vertices(); ++v) {
          const double d = (out.vertices.row(v) - torus.vertices.row(v)).norm();
          sag = std::max(sag, torus.vertices(v, 2) - out.vertices(v, 2));
          bool all_pinned = true;
          for (int a = 0; a < 8; ++a) all_pinned = all_pinned && rest.vertices(embedding.nodes(v, a), 0) <= 0.2;
          if (all_pinned) pinned_motion = std::max(pinned_motion, d);
        }
        EXPECT_LT(pinned_motion, 1e-12);
        EXPECT_GT(sag, 1e-3);
        std::printf("  %10d %6ld %8ld %12.5f %14.5f %12.5f %9.2f\n", resolution, static_cast<long>(summary.elements),
                    static_cast<long>(summary.vertices), summary.rest_volume, out.volume(), sag, seconds);
        previous_sag = sag;
      }
    }
  }
  EXPECT_GT(previous_sag, 0.0);
}

}  // namespace
}  // namespace sinew
