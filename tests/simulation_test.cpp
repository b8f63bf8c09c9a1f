// run_scene on small scenes: complete outputs (read back by VTK itself), per-frame metrics,
// --resume equal to an uninterrupted run, unconverged frames reported, external loads balanced
// by the support reactions, keyframed motion, hex and tet versions; mass matrices.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sys/wait.h>

#include "io_test_support.hpp"
#include "sinew/element/mass.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/integrator/quasistatic_integrator.hpp"
#include "sinew/model/model.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {
namespace {

using nlohmann::json;
using test::TempDir;

// A 1 x 0.25 x 0.25 bar of 8 x 2 x 2 hexes, left end pinned, right end pulled 0.1 per frame.
json bar(const std::string& element = "hex") {
  json j = json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.25, 0.25]}, "cells": [8, 2, 2]},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.45},
    "boundary": [
      {"name": "left", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}},
      {"name": "right", "select": {"plane": {"point": [1, 0, 0], "normal": [1, 0, 0]}},
       "motion": {"type": "translate", "per_frame": [0.1, 0, 0]}}
    ],
    "solver": {"newton": {"convergence": "absolute", "tolerance": 1e-7}},
    "frames": 4
  })");
  j["mesh"]["element"] = element;
  return j;
}

// Writes the scene next to the outputs (the checkpoint fingerprints the file) and loads it.
Scene scene_in(const TempDir& dir, const json& j, const std::string& name = "scene.json") {
  return load_scene(dir.write(name, j.dump(2)));
}

RunSummary run(const Scene& scene, const std::filesystem::path& out = {}, std::optional<int> frames = {},
               bool resume = false) {
  RunOptions o;
  o.out_dir = out;
  o.frames = frames;
  o.resume = resume;
  return run_scene(scene, o);
}

json read_json(const std::filesystem::path& p) { return json::parse(test::read_file(p)); }

int exit_status(int status) { return WIFEXITED(status) ? WEXITSTATUS(status) : -1; }

bool python_has_vtk() { return exit_status(std::system("/usr/bin/python3 -c 'import vtk' > /dev/null 2>&1")) == 0; }

// ---- outputs

TEST(Simulation, WritesEveryFrameAndCompleteReports) {
  TempDir dir;
  const Scene scene = scene_in(dir, bar());
  const RunSummary s = run(scene, dir / "out");
  ASSERT_TRUE(s.all_converged());
  ASSERT_EQ(s.frames.size(), 4u);
  EXPECT_EQ(s.vertices, 9 * 3 * 3);
  EXPECT_EQ(s.elements, 32);
  EXPECT_NEAR(s.rest_volume, 0.0625, 1e-14);

  std::vector<std::string> expected = {"checkpoint.json", "frames.jsonl", "simulation.pvd", "summary.json"};
  for (int f = 0; f <= 4; ++f) {
    expected.push_back(fmt::format("frame_{:04d}.vtu", f));
    expected.push_back(fmt::format("surface_{:04d}.obj", f));
  }
  std::sort(expected.begin(), expected.end());
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir / "out")) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, expected);  // and no temporary file left behind

  // The .pvd lists every frame at its frame number.
  const std::string pvd = test::read_file(dir / "out/simulation.pvd");
  for (int f = 0; f <= 4; ++f)
    EXPECT_NE(pvd.find(fmt::format("timestep=\"{}\"", f)), std::string::npos) << pvd;
  EXPECT_NE(pvd.find("file=\"frame_0004.vtu\""), std::string::npos);

  // The surface .obj has the boundary's vertices at the final positions.
  std::ifstream obj(dir / "out/surface_0004.obj");
  int v_lines = 0;
  double max_x = 0.0;
  for (std::string line; std::getline(obj, line);) {
    if (line.rfind("v ", 0) != 0) continue;
    ++v_lines;
    max_x = std::max(max_x, std::stod(line.substr(2)));
  }
  EXPECT_EQ(v_lines, 9 * 3 * 3 - 7 * 1 * 1);  // all but the interior vertices
  EXPECT_NEAR(max_x, 1.4, 1e-12);             // the right end moved 4 x 0.1

  const json sum = read_json(dir / "out/summary.json");
  EXPECT_EQ(sum["vertices"], s.vertices);
  EXPECT_EQ(sum["elements"], 32);
  EXPECT_EQ(sum["element"], "hex8");
  EXPECT_EQ(sum["material"], "stable_neo_hookean");
  EXPECT_EQ(sum["frames_requested"], 4);
  EXPECT_EQ(sum["frames_completed"], 4);
  EXPECT_EQ(sum["all_converged"], true);
  EXPECT_EQ(sum["boundary"], json({"left", "right"}));
  int newton = 0, linear = 0;
  ASSERT_EQ(sum["frames"].size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    const json& f = sum["frames"][i];
    const FrameRecord& r = s.frames[i];
    EXPECT_EQ(f["frame"], static_cast<int>(i) + 1);
    EXPECT_EQ(f["converged"], true);
    EXPECT_EQ(f["failure"], "");
    EXPECT_EQ(f["newton_iterations"], r.newton_iterations);
    EXPECT_GE(r.newton_iterations, 1);
    EXPECT_EQ(f["linear_iterations"], r.linear_iterations);  // one per Newton step with CHOLMOD
    // A true-Hessian solve that fails (solver.projection "adaptive") is solved again, projected.
    // ... plus one per retried true Hessian and one per tangent prediction (the first frame's).
    EXPECT_EQ(r.linear_iterations, r.newton_iterations + static_cast<int>(r.counter("exact_hessian_fallbacks")) +
                                       static_cast<int>(r.counter("tangent_predictor_linear_iterations")));
    EXPECT_LT(f["residual"].get<double>(), 1e-7);
    EXPECT_EQ(f["energy"].get<double>(), r.energy);
    EXPECT_GT(r.energy, 0.0);
    EXPECT_EQ(f["volume"].get<double>(), r.volume);
    EXPECT_GT(f["min_J"].get<double>(), 0.0);
    EXPECT_GT(f["seconds"].get<double>(), 0.0);
    EXPECT_GE(f["seconds"].get<double>(), f["assembly_seconds"].get<double>() + f["solve_seconds"].get<double>() - 1e-9);
    ASSERT_EQ(f["reactions"].size(), 2u);
    newton += r.newton_iterations;
    linear += r.linear_iterations;
    if (i > 0) {
      EXPECT_GT(r.energy, s.frames[i - 1].energy);  // stretched further each frame
    }
  }
  EXPECT_EQ(sum["total_newton_iterations"], newton);
  EXPECT_EQ(sum["total_linear_iterations"], linear);
  // At nu = 0.45 a stretched bar keeps its volume to within a few per cent.
  EXPECT_NEAR(s.frames.back().volume / s.rest_volume, 1.0, 0.05);

  const json cp = read_json(dir / "out/checkpoint.json");
  EXPECT_EQ(cp["frame"], 4);
  EXPECT_EQ(cp["x"].size(), static_cast<size_t>(3 * s.vertices));
}

TEST(Simulation, VtkReadsTheFramesOfHexAndTetRuns) {
  if (!python_has_vtk()) GTEST_SKIP() << "/usr/bin/python3 cannot import vtk (Debian package python3-vtk9)";
  const auto script = test::data_path("..") / "vtk_reader_check.py";
  for (const std::string element : {"hex", "tet"}) {
    SCOPED_TRACE(element);
    TempDir dir;
    const RunSummary s = run(scene_in(dir, bar(element)), dir / "out", 2);
    ASSERT_TRUE(s.all_converged());
    for (const char* frame : {"frame_0000.vtu", "frame_0002.vtu"}) {
      const std::string command = fmt::format(
          "/usr/bin/python3 '{}' '{}' --points {} --cells {} --arrays displacement J energy_density stress_norm energy "
          "--positive-volumes",
          script.string(), (dir / "out" / frame).string(), s.vertices, s.elements);
      EXPECT_EQ(exit_status(std::system(command.c_str())), 0) << command;
    }
  }
}

TEST(Simulation, ProgressReportsFramesAndNewtonIterations) {
  TempDir dir;
  const Scene scene = scene_in(dir, bar());
  int done = 0, last_iteration = 0, bad_records = 0, bad_iterations = 0;
  double elapsed = 0.0;
  RunOptions o;
  o.progress = [&](const ProgressEvent& e) {
    EXPECT_EQ(e.frames, 4);
    EXPECT_GE(e.elapsed, elapsed);
    elapsed = e.elapsed;
    if (e.frame_done) {
      // The record is valid during the call.
      if (e.record == nullptr || e.record->frame != e.frame || !e.record->converged) ++bad_records;
      EXPECT_EQ(e.frame, ++done);
      last_iteration = 0;
    } else {
      if (e.newton_iteration != 0 && e.newton_iteration != last_iteration + 1) ++bad_iterations;
      last_iteration = e.newton_iteration;
    }
  };
  const RunSummary s = run_scene(scene, o);
  EXPECT_EQ(done, 4);
  EXPECT_EQ(bad_records, 0);
  EXPECT_EQ(bad_iterations, 0);
  EXPECT_EQ(s.frames.size(), 4u);
  EXPECT_TRUE(dir.entries() == std::vector<std::string>{"scene.json"}) << "wrote files without an output folder";
}

// ---- resume

TEST(Simulation, ResumeGivesTheUninterruptedResult) {
  for (const std::string kind : {"cholmod", "pcg"}) {
    SCOPED_TRACE(kind);
    TempDir dir;
    json j = bar();
    j["solver"]["linear"] = {{"kind", kind}, {"tolerance", 1e-6}};
    const Scene scene = scene_in(dir, j);
    const RunSummary full = run(scene, dir / "full");
    ASSERT_TRUE(full.all_converged());
    const RunSummary half = run(scene, dir / "resumed", 2);
    ASSERT_EQ(half.frames.size(), 2u);
    EXPECT_FALSE(std::filesystem::exists(dir / "resumed/frame_0003.vtu"));
    const RunSummary resumed = run(scene, dir / "resumed", 4, true);
    ASSERT_EQ(resumed.frames.size(), 4u);
    ASSERT_TRUE(resumed.all_converged());
    // Same state to the last bit: the checkpoint stores round-trip doubles and assembly is
    // deterministic.
    EXPECT_EQ((resumed.x - full.x).cwiseAbs().maxCoeff(), 0.0);
    for (size_t i = 0; i < 4; ++i) {
      EXPECT_EQ(resumed.frames[i].newton_iterations, full.frames[i].newton_iterations);
      EXPECT_EQ(resumed.frames[i].energy, full.frames[i].energy);
    }
    EXPECT_EQ(test::read_file(dir / "resumed/frame_0004.vtu"), test::read_file(dir / "full/frame_0004.vtu"));
    const json sum = read_json(dir / "resumed/summary.json");
    EXPECT_EQ(sum["frames"].size(), 4u);
    EXPECT_EQ(sum["frames"][0]["newton_iterations"], full.frames[0].newton_iterations);
    const std::string pvd = test::read_file(dir / "resumed/simulation.pvd");
    size_t datasets = 0;
    for (size_t at = pvd.find("<DataSet "); at != std::string::npos; at = pvd.find("<DataSet ", at + 1)) ++datasets;
    EXPECT_EQ(datasets, 5u);
  }
}

TEST(Simulation, ResumeRefusesAChangedSceneOrAMissingCheckpoint) {
  TempDir dir;
  const Scene scene = scene_in(dir, bar());
  test::expect_contains(test::error_message([&] { run(scene, dir / "none", 4, true); }),
                        {"checkpoint.json", "no checkpoint to resume from"});
  EXPECT_FALSE(std::filesystem::exists(dir / "none"));
  run(scene, dir / "out", 1);
  json j = bar();
  j["frames"] = 5;
  const Scene changed = scene_in(dir, j);  // same file, new content
  test::expect_contains(test::error_message([&] { run(changed, dir / "out", 5, true); }), {"the scene file changed"});
}

// ---- failures are reported, never accepted

TEST(Simulation, UnconvergedFrameIsReportedAndStopsTheRun) {
  TempDir dir;
  json j = bar();
  j["solver"]["newton"] = {{"convergence", "absolute"}, {"tolerance", 1e-9}, {"max_iterations", 1}};
  j["boundary"][1]["motion"]["per_frame"] = {0.8, 0, 0};
  const Scene scene = scene_in(dir, j);
  const RunSummary s = run(scene, dir / "out");
  ASSERT_EQ(s.frames.size(), 1u);  // frames 2-4 would start from an unsolved state
  EXPECT_FALSE(s.all_converged());
  const FrameRecord& r = s.frames[0];
  EXPECT_FALSE(r.converged);
  EXPECT_GT(r.residual, 1e-9);
  test::expect_contains(r.failure, {"no convergence in 1 Newton iterations", "even with the frame's motion split into steps of 1/64"});
  // The whole step, then 6 halvings, each one Newton step.
  EXPECT_LE(r.newton_iterations, 1 + kMaxMotionSplits);
  const json sum = read_json(dir / "out/summary.json");
  EXPECT_EQ(sum["all_converged"], false);
  EXPECT_EQ(sum["frames"][0]["converged"], false);
  EXPECT_EQ(sum["frames"][0]["failure"], r.failure);
  EXPECT_TRUE(std::filesystem::exists(dir / "out/frame_0001.vtu"));  // for inspection
  EXPECT_FALSE(std::filesystem::exists(dir / "out/checkpoint.json"));  // never resumed from
}

TEST(Simulation, LargeFrameStepsAreSplitUntilTheyConverge) {
  // The whole 3.4x stretch in one frame: with at most 15 Newton iterations per solve, too far
  // for one solve from rest, so the motion is halved and solved in substeps.
  TempDir dir;
  json j = bar();
  j["boundary"][1]["motion"]["per_frame"] = {2.4, 0, 0};
  j["frames"] = 1;
  j["solver"]["newton"] = {{"convergence", "absolute"}, {"tolerance", 1e-6}, {"max_iterations", 15}};
  const RunSummary s = run(scene_in(dir, j));
  ASSERT_TRUE(s.all_converged()) << s.frames[0].failure;
  EXPECT_GT(s.frames[0].substeps, 1);
  EXPECT_NEAR(s.x.reshaped(3, s.vertices).row(0).maxCoeff(), 1.0 + 2.4, 1e-12);  // the moved end
}

// The predictor (the last converged increment, extrapolated) starts each frame nearer its
// equilibrium: fewer Newton iterations to the same answer.
TEST(Simulation, PredictorCutsNewtonIterationsToTheSameAnswer) {
  json j = bar();
  j["boundary"][1]["motion"]["per_frame"] = {0.3, 0, 0};
  j["frames"] = 5;
  j["solver"]["newton"] = {{"residual_tolerance", 1e-10}, {"step_tolerance", 1e-8}};
  j["solver"]["predictor"] = "none";
  const RunSummary plain = run(parse_scene(j, "bar.json"));
  j["solver"]["predictor"] = "extrapolate";
  const RunSummary predicted = run(parse_scene(j, "bar.json"));
  ASSERT_TRUE(plain.all_converged());
  ASSERT_TRUE(predicted.all_converged());
  int n_plain = 0, n_predicted = 0;
  for (size_t i = 0; i < plain.frames.size(); ++i) {
    n_plain += plain.frames[i].newton_iterations;
    n_predicted += predicted.frames[i].newton_iterations;
  }
  EXPECT_LT(n_predicted, n_plain);
  EXPECT_LT((plain.x - predicted.x).cwiseAbs().maxCoeff(), 1e-7);  // 1e-7 of the bar's length
  EXPECT_GT(predicted.frames.back().counters.size(), 0u);  // "predicted_steps" recorded
}

// The default predictor ("auto") adds the tangent predictor where there is nothing to
// extrapolate: the first frame starts from the linearised solution instead of a bar whose end
// layer alone carries the motion.
TEST(Simulation, TangentPredictorCutsTheFirstFramesNewtonIterations) {
  json j = bar();
  j["boundary"][1]["motion"]["per_frame"] = {0.3, 0.05, 0};
  j["frames"] = 3;
  j["solver"]["newton"] = {{"residual_tolerance", 1e-10}, {"step_tolerance", 1e-8}};
  j["solver"]["predictor"] = "extrapolate";
  const RunSummary extrapolated = run(parse_scene(j, "bar.json"));
  j["solver"].erase("predictor");
  const RunSummary automatic = run(parse_scene(j, "bar.json"));
  ASSERT_TRUE(extrapolated.all_converged());
  ASSERT_TRUE(automatic.all_converged());
  EXPECT_LT(automatic.frames[0].newton_iterations, extrapolated.frames[0].newton_iterations);
  EXPECT_EQ(automatic.frames[0].counter("tangent_predicted_steps"), 1.0);
  EXPECT_EQ(automatic.frames[2].counter("predicted_steps"), 1.0);
  EXPECT_LT((automatic.x - extrapolated.x).cwiseAbs().maxCoeff(), 1e-7);
}

// A solve that fails with nothing changing inside the frame (no prescribed motion, constant
// loads) is not repeated as smaller 'substeps': each would be the same solve.
TEST(Simulation, FailedSolveWithNothingToSplitIsNotRepeated) {
  json j = bar();
  j["boundary"].erase(1);
  j["loads"] = {{"gravity", {0, 0, -9.81}}};
  j["frames"] = 1;
  j["solver"]["newton"] = {{"residual_tolerance", 1e-12}, {"max_iterations", 1}};
  const RunSummary s = run(parse_scene(j, "hanging.json"));
  ASSERT_EQ(s.frames.size(), 1u);
  EXPECT_FALSE(s.frames[0].converged);
  EXPECT_EQ(s.frames[0].newton_iterations, 1);  // one solve, not 1 + kMaxMotionSplits
  test::expect_contains(s.frames[0].failure, {"not split: no motion, load or obstacle changes within the step"});
}

TEST(Simulation, ModelProblemsSurfaceBeforeAnythingIsWritten) {
  TempDir dir;
  json j = bar();
  j["boundary"][1]["select"] = {{"box", {{"min", {5, 5, 5}}, {"max", {6, 6, 6}}}}};
  const Scene scene = scene_in(dir, j);
  test::expect_contains(test::error_message([&] { run(scene, dir / "out"); }),
                        {"scene.json: /boundary/1/select: selection contains no vertex"});
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

// ---- loads and reactions

struct Balance {
  RunSummary summary;
  Eigen::Vector3d reaction = Eigen::Vector3d::Zero();  // sum over boundary conditions
};

Balance solve_loaded(const json& loads, const std::string& element) {
  TempDir dir;
  json j = json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.5, 0.25]}, "cells": [4, 2, 2]},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.3},
    "density": 800,
    "boundary": [{"name": "wall", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}}],
    "solver": {"newton": {"convergence": "absolute", "tolerance": 1e-9}}
  })");
  j["mesh"]["element"] = element;
  j["loads"] = loads;
  Balance b;
  b.summary = run(scene_in(dir, j));
  EXPECT_TRUE(b.summary.all_converged());
  for (const auto& r : b.summary.frames.back().reactions) b.reaction += r;
  return b;
}

TEST(Simulation, GravityIsDensityTimesVolumeAndTheWallCarriesIt) {
  for (const std::string element : {"hex", "tet"}) {
    SCOPED_TRACE(element);
    const Balance b = solve_loaded(json::parse(R"({"gravity": [0, 0, -9.81]})"), element);
    const Eigen::Vector3d weight(0, 0, -800 * 9.81 * 0.125);
    EXPECT_LT((b.summary.external_force - weight).norm(), 1e-12 * weight.norm());
    EXPECT_LT((b.reaction + weight).norm(), 1e-8 * weight.norm()) << b.reaction.transpose();
  }
}

TEST(Simulation, PointLoadsActOnEachSelectedVertex) {
  for (const std::string element : {"hex", "tet"}) {
    SCOPED_TRACE(element);
    // The free end x = 1 has 3 x 3 vertices.
    const Balance b = solve_loaded(
        json::parse(R"({"point": [{"select": {"plane": {"point": [1, 0, 0], "normal": [1, 0, 0]}}, "force": [2, 0, -1]}]})"), element);
    const Eigen::Vector3d total = 9 * Eigen::Vector3d(2, 0, -1);
    EXPECT_LT((b.summary.external_force - total).norm(), 1e-12);
    EXPECT_LT((b.reaction + total).norm(), 1e-8 * total.norm()) << b.reaction.transpose();
  }
}

TEST(Simulation, TractionIsForcePerAreaAndTheWallCarriesIt) {
  for (const std::string element : {"hex", "tet"}) {
    SCOPED_TRACE(element);
    // End face 0.5 x 0.25, and the top face z = 0.25 (1 x 0.5) with a shear traction.
    const Balance b = solve_loaded(json::parse(R"({"traction": [
        {"select": {"plane": {"point": [1, 0, 0], "normal": [1, 0, 0]}}, "traction": [1000, 0, 400]},
        {"select": {"plane": {"point": [0, 0, 0.25], "normal": [0, 0, 1]}}, "traction": [0, 300, 0]}]})"),
                                   element);
    const Eigen::Vector3d total = 0.125 * Eigen::Vector3d(1000, 0, 400) + 0.5 * Eigen::Vector3d(0, 300, 0);
    EXPECT_LT((b.summary.external_force - total).norm(), 1e-12 * total.norm());
    EXPECT_LT((b.reaction + total).norm(), 1e-8 * total.norm()) << b.reaction.transpose();
  }
}

TEST(Simulation, TractionNodalForcesIntegrateTheShapeFunctions) {
  // One hexahedron: a uniform traction on a face puts A/4 on each of its corners. Its six tets
  // put A/3 per triangle corner. Gravity puts rho V / 8 on each hex corner.
  json j = json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [2, 1, 1]}, "cells": [1, 1, 1]},
    "material": {"family": "stable_neo_hookean", "E": 1, "nu": 0.3},
    "density": 3,
    "loads": {"gravity": [0, 0, -1], "traction": [{"select": {"plane": {"point": [2, 0, 0], "normal": [1, 0, 0]}}, "traction": [8, 0, 0]}]}
  })");
  const Scene hex = parse_scene(j, "s.json");
  const Discretization disc(build_scene_mesh(hex));
  const Eigen::VectorXd f = external_forces(hex, disc, boundary_surface(disc.mesh()));
  for (Eigen::Index v = 0; v < disc.mesh().num_vertices(); ++v) {
    const double expected_x = disc.mesh().vertices(v, 0) == 2.0 ? 8.0 * 1.0 / 4.0 : 0.0;
    EXPECT_NEAR(f(3 * v), expected_x, 1e-13);
    EXPECT_NEAR(f(3 * v + 2), -3.0 * 2.0 / 8.0, 1e-13);
  }
  j["mesh"]["element"] = "tet";
  const Scene tet = parse_scene(j, "s.json");
  const Discretization tdisc(build_scene_mesh(tet));
  const Eigen::VectorXd g = external_forces(tet, tdisc, boundary_surface(tdisc.mesh()));
  double end_force = 0.0, corner_min = 1e9, corner_max = 0.0;
  for (Eigen::Index v = 0; v < tdisc.mesh().num_vertices(); ++v) {
    if (tdisc.mesh().vertices(v, 0) != 2.0) continue;
    end_force += g(3 * v);
    corner_min = std::min(corner_min, g(3 * v));
    corner_max = std::max(corner_max, g(3 * v));
  }
  EXPECT_NEAR(end_force, 8.0, 1e-13);
  // Two triangles of area 1/2: corners on the diagonal get 2 * (1/2) / 3 * 8, the others half.
  EXPECT_NEAR(corner_max, 8.0 / 3.0, 1e-13);
  EXPECT_NEAR(corner_min, 4.0 / 3.0, 1e-13);
}

TEST(Simulation, StretchReactionsAreEqualAndOpposite) {
  TempDir dir;
  const RunSummary s = run(scene_in(dir, bar()));
  for (const auto& f : s.frames) {
    ASSERT_EQ(f.reactions.size(), 2u);
    EXPECT_LT(f.reactions[0].x(), 0.0);  // the left wall holds the bar back
    EXPECT_GT(f.reactions[1].x(), 0.0);  // the right end pulls it
    EXPECT_LT((f.reactions[0] + f.reactions[1]).norm(), 1e-6 * f.reactions[1].norm());
  }
  // Small strain: the first 10 % stretch pulls with about E A strain (5 % looser or stiffer).
  EXPECT_NEAR(s.frames[0].reactions[1].x(), 1e5 * 0.0625 * 0.1, 0.1 * 1e5 * 0.0625 * 0.1);
}

// ---- motions and element kinds

TEST(Simulation, KeyframedMotionInterpolatesAndHolds) {
  // Every vertex follows the keyframes, so each frame's state is the interpolated transform.
  TempDir dir;
  json j = bar();
  j["boundary"] = json::parse(R"([{"select": {"box": {"min": [-1, -1, -1], "max": [2, 2, 2]}},
    "motion": {"type": "keyframes", "keys": [
      {"frame": 0},
      {"frame": 2, "translation": [0.2, 0, 0.4], "rotation": {"axis": [0, 0, 1], "degrees": 90}}]}}])");
  const Scene scene = scene_in(dir, j);
  const VolumeMesh mesh = build_scene_mesh(scene);
  for (const auto& [frames, degrees, fraction] : {std::tuple{1, 45.0, 0.5}, std::tuple{3, 90.0, 1.0}}) {
    const RunSummary s = run(scene, {}, frames);
    ASSERT_TRUE(s.all_converged());
    EXPECT_EQ(s.frames.back().newton_iterations, 0);  // nothing free to solve for
    const Eigen::Matrix3d R = Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d t = fraction * Eigen::Vector3d(0.2, 0, 0.4);
    for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) {
      const Eigen::Vector3d expected = R * mesh.vertices.row(v).transpose() + t;
      EXPECT_LT((s.x.segment<3>(3 * v) - expected).norm(), 1e-12) << "frame " << frames << " vertex " << v;
    }
  }
}

TEST(Simulation, TransformAtInterpolatesKeyframes) {
  Keyframes k;
  k.keys = {{1.0, Eigen::Quaterniond::Identity(), Eigen::Vector3d(1, 0, 0)},
            {3.0, Eigen::Quaterniond(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX())), Eigen::Vector3d(3, 2, 0)}};
  const RigidMotion m = k;
  EXPECT_LT((transform_at(m, 0.0).t - Eigen::Vector3d(1, 0, 0)).norm(), 1e-15);  // held before
  EXPECT_LT((transform_at(m, 2.5).t - Eigen::Vector3d(2.5, 1.5, 0)).norm(), 1e-15);
  EXPECT_NEAR(Eigen::AngleAxisd(transform_at(m, 2.0).R).angle(), std::numbers::pi / 4, 1e-14);
  EXPECT_NEAR(Eigen::AngleAxisd(transform_at(m, 2.5).R).angle(), 3 * std::numbers::pi / 8, 1e-14);
  EXPECT_LT((transform_at(m, 9.0).t - Eigen::Vector3d(3, 2, 0)).norm(), 1e-15);  // held after
}

TEST(Simulation, HexAndTetVersionsAgree) {
  TempDir dir;
  const RunSummary hex = run(scene_in(dir, bar("hex"), "hex.json"));
  const RunSummary tet = run(scene_in(dir, bar("tet"), "tet.json"));
  ASSERT_TRUE(hex.all_converged());
  ASSERT_TRUE(tet.all_converged());
  EXPECT_EQ(hex.vertices, tet.vertices);
  EXPECT_EQ(tet.elements, 6 * hex.elements);
  EXPECT_NEAR(tet.rest_volume, hex.rest_volume, 1e-14);
  // Same boundary motion, similar response (linear tets are stiffer on so coarse a mesh).
  const double f_hex = hex.frames.back().reactions[1].x(), f_tet = tet.frames.back().reactions[1].x();
  EXPECT_GT(f_tet, 0.9 * f_hex);
  EXPECT_LT(f_tet, 1.5 * f_hex);
  EXPECT_NEAR(tet.frames.back().volume / hex.frames.back().volume, 1.0, 0.02);
}

// ---- mass matrices (fem/mass.hpp)

void check_masses(const VolumeMesh& mesh, double density) {
  const Discretization disc(mesh);
  double volume = 0.0;
  for (Eigen::Index e = 0; e < disc.num_elements(); ++e) volume += disc.rest_volume(e);
  const Eigen::VectorXd lumped = lumped_mass(disc, density);
  ASSERT_EQ(lumped.size(), mesh.num_vertices());
  EXPECT_NEAR(lumped.sum(), density * volume, 1e-12 * density * volume);
  EXPECT_GT(lumped.minCoeff(), 0.0);
  const Eigen::SparseMatrix<double> M = consistent_mass(disc, density);
  ASSERT_EQ(M.rows(), 3 * mesh.num_vertices());
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(M.cols());
  // Each of the three components carries the whole mass once.
  EXPECT_NEAR(ones.dot(M * ones), 3.0 * density * volume, 1e-12 * density * volume);
  EXPECT_NEAR((Eigen::SparseMatrix<double>(M.transpose()) - M).norm(), 0.0, 1e-14 * M.norm());
  // Lumping is the row sum, and a translation's momentum is the same either way.
  const Eigen::VectorXd row_sums = M * ones;
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(row_sums(3 * v + i), lumped(v), 1e-12 * lumped(v));
  // Positive definite: a random velocity has positive kinetic energy.
  const Eigen::VectorXd u = Eigen::VectorXd::Random(M.cols());
  EXPECT_GT(u.dot(M * u), 0.0);
}

TEST(Mass, LumpedAndConsistentMassesCarryDensityTimesVolume) {
  const VolumeMesh box = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1, 0.5), Eigen::Vector3i(4, 3, 2));
  check_masses(box, 1000.0);
  check_masses(tetrahedralize_hexes(box), 1000.0);
  // Irregular meshes: a distorted lattice (non-parallelepiped hexes) and tets from file.
  VolumeMesh distorted = box;
  for (Eigen::Index v = 0; v < distorted.num_vertices(); ++v)
    distorted.vertices.row(v) += 0.05 * Eigen::RowVector3d(std::sin(7.0 * v), std::cos(3.0 * v), std::sin(5.0 * v));
  check_masses(distorted, 2.5);
  check_masses(read_volume_mesh(test::data_path("tet5.mesh")), 7.0);
  check_masses(read_volume_mesh(test::data_path("hex2.mesh")), 7.0);
}

TEST(Mass, UnitCubeValuesAreExact) {
  const Discretization hex(box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i(1, 1, 1)));
  EXPECT_TRUE(lumped_mass(hex, 8.0).isApprox(Eigen::VectorXd::Ones(8)));
  // Trilinear hex: M_ab = rho V (1 + [same x]) (1 + [same y]) (1 + [same z]) / 216, which 2x2x2
  // Gauss integrates exactly.
  const Eigen::MatrixXd M = Eigen::MatrixXd(consistent_mass(hex, 216.0));
  const auto& X = hex.mesh().vertices;
  for (int a = 0; a < 8; ++a)
    for (int b = 0; b < 8; ++b) {
      const int same = int(X(a, 0) == X(b, 0)) + int(X(a, 1) == X(b, 1)) + int(X(a, 2) == X(b, 2));
      EXPECT_NEAR(M(3 * a, 3 * b), double(1 << same), 1e-12) << a << " " << b;
      EXPECT_EQ(M(3 * a, 3 * b + 1), 0.0);  // components do not couple
    }
  // Tet: M_ab = rho V (1 + delta_ab) / 20.
  const Discretization tet(read_volume_mesh(test::data_path("tet5.mesh")));
  const Eigen::MatrixXd Mt = Eigen::MatrixXd(consistent_mass(tet, 1.0));
  double diagonal = 0.0;
  for (Eigen::Index e = 0; e < tet.num_elements(); ++e) diagonal += 4.0 * tet.rest_volume(e) / 10.0;  // 4 nodes x 2V/20
  EXPECT_NEAR(Mt.diagonal().sum() / 3.0, diagonal, 1e-14);
  EXPECT_THROW(lumped_mass(hex, -1.0), Error);
  EXPECT_THROW(consistent_mass(hex, std::nan("")), Error);
}

}  // namespace
}  // namespace sinew
