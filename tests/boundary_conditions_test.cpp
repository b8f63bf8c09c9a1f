// Per-component and direction boundary conditions, load/motion amplitudes, per-condition
// reactions and selector warnings, through the whole solver (run_scene).
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "io_test_support.hpp"
#include "sinew/assembly/problem.hpp"
#include "sinew/core/error.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/material/spec.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/model/model.hpp"
#include "sinew/motion/prescribed_motion.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {
namespace {

using nlohmann::json;
using test::TempDir;

RunSummary run_json(const json& j, const std::filesystem::path& file = "scene.json") {
  return run_scene(parse_scene(j, file), RunOptions{});
}

// Lateral stretch t of homogeneous uniaxial stress at axial stretch `stretch`: the root of
// P22(diag(stretch, t, t)) = 0 by bisection on the material's principal stresses (independent
// of any mesh), and the axial P11 there.
std::pair<double, double> uniaxial_stress(const Material& m, double stretch) {
  auto p22 = [&](double t) { return m.grad_stretch(Vec3(stretch, t, t))(1); };
  double lo = 0.2, hi = 1.5;
  EXPECT_LT(p22(lo) * p22(hi), 0.0);
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (p22(lo) * p22(mid) <= 0.0 ? hi : lo) = mid;
  }
  const double t = 0.5 * (lo + hi);
  return {t, m.grad_stretch(Vec3(stretch, t, t))(0)};
}

// A 2 x 1 x 1 bar on symmetry rollers (x = 0: u_x, y = 0: u_y, z = 0: u_z), its end x = 2
// displaced along x: uniaxial stress, homogeneous on any mesh.
json roller_bar(const std::string& family, double end_displacement) {
  json j = json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [2, 1, 1]}, "cells": [4, 2, 2]},
    "boundary": [
      {"name": "symmetry x", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}, "components": ["x"]},
      {"name": "symmetry y", "select": {"plane": {"point": [0, 0, 0], "normal": [0, -1, 0]}}, "components": ["y"]},
      {"name": "symmetry z", "select": {"plane": {"point": [0, 0, 0], "normal": [0, 0, -1]}}, "components": ["z"]},
      {"name": "pull", "select": {"plane": {"point": [2, 0, 0], "normal": [1, 0, 0]}}, "components": ["x"],
       "motion": {"type": "displace", "displacement": [0, 0, 0]}}
    ],
    "solver": {"newton": {"residual_tolerance": 1e-12, "step_tolerance": 1e-10}},
    "frames": 3
  })");
  j["material"] = {{"family", family}, {"E", 1e5}, {"nu", 0.4}};
  j["boundary"][3]["motion"]["displacement"] = {end_displacement, 0, 0};
  return j;
}

class UniaxialStress : public ::testing::TestWithParam<std::string> {};

TEST_P(UniaxialStress, RollersGiveTheClosedFormLateralStretchAndForce) {
  const json j = roller_bar(GetParam(), 0.6);  // axial stretch 1.3 at the last frame
  const Scene scene = parse_scene(j, "bar.json");
  const RunSummary s = run_scene(scene, RunOptions{});
  ASSERT_EQ(s.frames.size(), 3u);
  const auto built = build_material_detailed(scene.material);
  const Eigen::MatrixX3d rest = build_scene_mesh(scene).vertices;
  for (const FrameRecord& f : s.frames) ASSERT_TRUE(f.converged) << f.failure;
  // The "displace" motion ramps by default: frame k is at k/3 of the displacement.
  for (int k = 1; k <= 3; ++k) {
    const double stretch = 1.0 + 0.3 * k / 3.0;
    const auto [t, P11] = uniaxial_stress(*built.material, stretch);
    const FrameRecord& f = s.frames[k - 1];
    // The pulled end's support pulls with P11 x rest area (1 x 1), along x only; the x-roller
    // holds the other end with the opposite force; the lateral rollers carry nothing.
    EXPECT_NEAR(f.reactions[3](0), P11, 1e-8 * std::abs(P11)) << "frame " << k;
    EXPECT_EQ(f.reactions[3](1), 0.0);
    EXPECT_EQ(f.reactions[3](2), 0.0);
    EXPECT_NEAR(f.reactions[0](0), -P11, 1e-8 * std::abs(P11));
    EXPECT_NEAR(f.reactions[1].norm(), 0.0, 1e-8 * std::abs(P11));
    EXPECT_NEAR(f.reactions[2].norm(), 0.0, 1e-8 * std::abs(P11));
    EXPECT_NEAR(f.volume, 2.0 * stretch * t * t, 1e-8);
    if (k == 3) {
      for (Eigen::Index v = 0; v < rest.rows(); ++v) {
        const Eigen::Vector3d X = rest.row(v).transpose();
        const Eigen::Vector3d expected(stretch * X(0), t * X(1), t * X(2));
        EXPECT_LT((s.x.segment<3>(3 * v) - expected).norm(), 1e-8) << "vertex " << v;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Families, UniaxialStress, ::testing::Values("neo_hookean", "stable_neo_hookean"));

// The same bar turned by 30 degrees about z, its two x- and y-rollers now direction conditions
// on inclined planes: the answer is the turned answer, the reactions turned with it.
TEST(DirectionCondition, InclinedRollersGiveTheRotatedAnswer) {
  const double angle = std::numbers::pi / 6;
  const Mat3 R = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  TempDir dir;
  // The turned lattice as a legacy VTK file.
  VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d(2, 1, 1), Eigen::Vector3i(4, 2, 2));
  {
    std::string text = "# vtk DataFile Version 2.0\nturned bar\nASCII\nDATASET UNSTRUCTURED_GRID\n";
    text += fmt::format("POINTS {} double\n", mesh.num_vertices());
    for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) {
      const Eigen::Vector3d p = R * mesh.vertices.row(v).transpose();
      text += fmt::format("{:.17g} {:.17g} {:.17g}\n", p(0), p(1), p(2));
    }
    text += fmt::format("CELLS {} {}\n", mesh.num_elements(), 9 * mesh.num_elements());
    for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) {
      text += "8";
      for (int a = 0; a < 8; ++a) text += fmt::format(" {}", mesh.elements(e, a));
      text += "\n";
    }
    text += fmt::format("CELL_TYPES {}\n", mesh.num_elements());
    for (Eigen::Index e = 0; e < mesh.num_elements(); ++e) text += "12\n";
    dir.write("turned.vtk", text);
  }
  const Eigen::Vector3d ex = R.col(0), ey = R.col(1);
  auto vec = [](const Eigen::Vector3d& v) { return json::array({v(0), v(1), v(2)}); };
  json turned = roller_bar("stable_neo_hookean", 0.6);
  turned["mesh"] = {{"file", "turned.vtk"}};
  auto& b = turned["boundary"];
  b[0]["select"] = {{"plane", {{"point", {0, 0, 0}}, {"normal", vec(-ex)}}}};
  b[0].erase("components");
  b[0]["direction"] = vec(ex);
  b[1]["select"] = {{"plane", {{"point", {0, 0, 0}}, {"normal", vec(-ey)}}}};
  b[1].erase("components");
  b[1]["direction"] = vec(ey);
  b[3]["select"] = {{"plane", {{"point", vec(2.0 * ex)}, {"normal", vec(ex)}}}};
  b[3].erase("components");
  b[3]["direction"] = vec(ex);
  b[3]["motion"]["displacement"] = vec(0.6 * ex);
  const RunSummary axis = run_json(roller_bar("stable_neo_hookean", 0.6), dir.path() / "bar.json");
  const RunSummary incl = run_json(turned, dir.path() / "turned.json");
  ASSERT_EQ(incl.frames.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    ASSERT_TRUE(incl.frames[k].converged) << incl.frames[k].failure;
    for (size_t c = 0; c < 4; ++c)
      EXPECT_LT((incl.frames[k].reactions[c] - R * axis.frames[k].reactions[c]).norm(), 1e-7)
          << "frame " << k + 1 << " condition " << c;
  }
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
    EXPECT_LT((incl.x.segment<3>(3 * v) - R * axis.x.segment<3>(3 * v)).norm(), 1e-9) << "vertex " << v;
}

// The rotated frames of a problem: its gradient and Hessian are those of the global energy in
// local coordinates (g_l = Q^T g, H_l = Q^T H Q), checked against central differences of the
// energy along local directions mapped back by to_global.
TEST(DirectionCondition, ProblemDerivativesInVertexFrames) {
  VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 1, 1), Eigen::Vector3i(2, 2, 2));
  auto disc = std::make_shared<Discretization>(mesh, "test");
  MaterialSpec spec;
  spec.family = "stable_neo_hookean";
  spec.target = YoungPoisson{1.0, 0.3};
  const auto built = build_material_detailed(spec);
  Problem p(mesh.num_vertices());
  p.add_form(std::make_shared<ElasticForm>(disc, built.material, Projection::None));
  std::vector<std::pair<int, Mat3>> frames;
  for (int v : {0, 5, 13, 26}) frames.emplace_back(v, vertex_frame(Eigen::Vector3d(1, 2, v == 5 ? -3 : 3)));
  p.set_vertex_frames(frames);
  std::srand(7);
  Eigen::VectorXd x = mesh.rest_positions() + 0.1 * Eigen::VectorXd::Random(3 * mesh.num_vertices());
  const Eigen::VectorXd g = p.gradient(x);
  const Eigen::SparseMatrix<double> H = *p.hessian(x).matrix();
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::VectorXd d_local = Eigen::VectorXd::Random(x.size());
    Eigen::VectorXd d = d_local;
    p.to_global(d);
    const double h = 1e-5;
    const double fd = (p.value(x + h * d) - p.value(x - h * d)) / (2 * h);
    EXPECT_NEAR(fd, g.dot(d_local), 1e-6 * std::max(1.0, std::abs(fd)));
    const Eigen::VectorXd gfd = (p.gradient(x + h * d) - p.gradient(x - h * d)) / (2 * h);
    EXPECT_LT((gfd - H * d_local).norm(), 1e-5 * std::max(1.0, gfd.norm()));
  }
}

// Load control: a point load with amplitude "ramp" over 4 frames is k/4 of the force at frame k;
// an explicit amplitude goes up and back down; the supports carry exactly the applied load.
TEST(Amplitude, RampsLoadsOverFrames) {
  json j = json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.2, 0.2]}, "cells": [5, 1, 1]},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.3},
    "boundary": [{"name": "wall", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}}],
    "loads": {"point": [{"select": {"plane": {"point": [1, 0, 0], "normal": [1, 0, 0]}}, "force": [0, 0, -1],
                         "amplitude": "ramp"}],
              "gravity": {"acceleration": [0, 0, -10], "amplitude": [[0, 0], [2, 1], [4, 0]]}},
    "density": 100,
    "frames": 4
  })");
  const RunSummary s = run_json(j);
  ASSERT_EQ(s.frames.size(), 4u);
  const double weight = 100 * 0.04 * 10;  // density x volume x g
  const double gravity_factor[] = {0.5, 1.0, 0.5, 0.0};
  for (int k = 1; k <= 4; ++k) {
    const FrameRecord& f = s.frames[k - 1];
    ASSERT_TRUE(f.converged) << f.failure;
    const double load = 4 * (k / 4.0) + weight * gravity_factor[k - 1];  // 4 end vertices x 1 N x ramp
    EXPECT_NEAR(f.external_force(2), -load, 1e-9 * load) << "frame " << k;
    EXPECT_NEAR(f.reactions[0](2), load, 1e-6 * load) << "frame " << k;
  }
  EXPECT_NEAR(s.external_force(2), -(4 + weight), 1e-9 * (4 + weight));  // run level: amplitude 1
}

TEST(Amplitude, BadAmplitudesNameTheField) {
  const std::string base = R"({"mesh": {"box": {"min": [0,0,0], "max": [1,1,1]}, "cells": [1,1,1]},
    "material": {"family": "stable_neo_hookean", "E": 1, "nu": 0.3},
    "loads": {"point": [{"select": {"indices": [0]}, "force": [1,0,0], "amplitude": AMP}]}})";
  auto error_of = [&](const std::string& amp) {
    std::string text = base;
    text.replace(text.find("AMP"), 3, amp);
    try {
      parse_scene(json::parse(text), "s.json");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of(R"("steps")").find("/loads/point/0/amplitude: unknown value 'steps'"), std::string::npos);
  EXPECT_NE(error_of("[]").find("/loads/point/0/amplitude: must be \"ramp\" or a non-empty list"), std::string::npos);
  EXPECT_NE(error_of("[[0, 1], [0, 2]]").find("/loads/point/0/amplitude: point 1 is not after point 0"), std::string::npos);
  EXPECT_NE(error_of("[[0, 1, 2]]").find("/loads/point/0/amplitude/0: must be a [frame, factor] pair"), std::string::npos);
}

TEST(ComponentConditions, BadConditionsNameTheField) {
  auto error_of = [](const std::string& boundary) {
    const std::string text = R"({"mesh": {"box": {"min": [0,0,0], "max": [1,1,1]}, "cells": [2,2,2]},
      "material": {"family": "stable_neo_hookean", "E": 1, "nu": 0.3}, "boundary": [)" + boundary + "]}";
    try {
      const Scene s = parse_scene(json::parse(text), "s.json");
      build_model(s);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string sel = R"("select": {"indices": [0]})";
  EXPECT_NE(error_of("{" + sel + R"(, "components": ["x", "w"]})").find("/boundary/0/components/1: unknown component 'w'"),
            std::string::npos);
  EXPECT_NE(error_of("{" + sel + R"(, "components": ["x", "x"]})").find("/boundary/0/components/1: component 'x' is listed twice"),
            std::string::npos);
  EXPECT_NE(error_of("{" + sel + R"(, "components": []})").find("/boundary/0/components: must be a non-empty list"),
            std::string::npos);
  EXPECT_NE(error_of("{" + sel + R"(, "components": ["x"], "direction": [1, 0, 0]})").find("/boundary/0/direction: give either"),
            std::string::npos);
  EXPECT_NE(error_of("{" + sel + R"(, "direction": [0, 0, 0]})").find("/boundary/0/direction: must be non-zero"),
            std::string::npos);
  // The same coordinate moved by two conditions; different coordinates are fine.
  const std::string moving = R"("motion": {"type": "translate", "per_frame": [0.1, 0, 0]})";
  EXPECT_NE(error_of("{" + sel + R"(, "components": ["x"]}, {)" + sel + ", " + moving + R"(, "components": ["x", "y"]})")
                .find("/boundary/1/select: vertex 0 is also prescribed along (1, 0, 0) by /boundary/0 with a different motion"),
            std::string::npos);
  EXPECT_EQ(error_of("{" + sel + R"(, "components": ["x"]}, {)" + sel + ", " + moving + R"(, "components": ["y"]})"),
            "no error");
  // Directions at one vertex must be orthogonal (an inclined roller and a symmetry plane at right
  // angles are fine).
  EXPECT_NE(error_of("{" + sel + R"(, "direction": [1, 1, 0]}, {)" + sel + R"(, "components": ["x"]})")
                .find("/boundary/1/select: vertex 0 is also prescribed by /boundary/0 along a direction at 45 degrees"),
            std::string::npos);
  EXPECT_EQ(error_of("{" + sel + R"(, "direction": [1, 1, 0]}, {)" + sel + R"(, "components": ["z"]})"), "no error");
}

// A selector that takes the whole body, and conditions that pin every coordinate, are legal
// but almost always mistakes: the run warns (summary.json "warnings", the warning callback),
// and --strict makes them errors.
TEST(SelectorWarnings, WholeBodySelectionAndFullyPinnedBodyAreReported) {
  json j = json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}, "cells": [2, 2, 2]},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.3},
    "boundary": [{"name": "oops", "select": {"plane": {"point": [0, 0, 0], "normal": [0, 0, 1]}}}],
    "frames": 1
  })");
  std::vector<std::string> warnings;
  RunOptions o;
  o.warning = [&](const std::string& w) { warnings.push_back(w); };
  const RunSummary s = run_scene(parse_scene(j, "pinned.json"), o);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("pinned.json: /boundary/0/select: boundary condition 'oops' selects every vertex"),
            std::string::npos);
  EXPECT_NE(warnings[1].find("fully pinned"), std::string::npos);
  EXPECT_EQ(s.warnings, warnings);
  o.strict = true;
  EXPECT_THROW(run_scene(parse_scene(j, "pinned.json"), o), Error);
  // Only the z coordinate everywhere (plane strain's u_z = 0 is a component of it): the selector
  // warning, but the body is not fully pinned.
  j["boundary"][0]["components"] = {"z"};
  j["boundary"].push_back({{"name", "base"}, {"select", {{"plane", {{"point", {0, 0, 0}}, {"normal", {-1, 0, 0}}}}}}});
  warnings.clear();
  o.strict = false;
  run_scene(parse_scene(j, "plane_strain.json"), o);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("selects every vertex"), std::string::npos);
}

}  // namespace
}  // namespace sinew
