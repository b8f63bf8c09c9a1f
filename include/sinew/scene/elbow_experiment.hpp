#pragma once
// Paper 000 §6, Fig. 2 and Fig. 10: elbow flexion. An arm (upper arm with a biceps bulge, elbow,
// forearm with a flexor bulge) is voxelised into a hexahedral lattice, two capsule bones
// (humerus fixed, radius/ulna turned about the elbow axis) drive it from 0 to 120 degrees over
// the frames, and reference-map self-contact keeps biceps and forearm apart.
// The arm is the shipped surface examples/meshes/arm.obj voxelised with mesh/voxelize.hpp
// (ElbowConfig::arm_surface), its vertices embedded in the lattice; the analytic signed distance
// arm_sdf() it was extracted from (scripts/make_arm_mesh.py) remains for runs without the file.
#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "sinew/contact/self_contact_form.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/triangle_surface.hpp"
#include "sinew/rig/rig.hpp"
#include "sinew/scene/experiments.hpp"

namespace sinew {

// Fig. 10 (SNH, nu = 0.488, torso/biceps, 45,809 hexahedra): averages per time step.
struct PaperElbowFigure {
  const char* family;
  double newton, cg, seconds;
};
inline constexpr std::array<PaperElbowFigure, 2> kPaperElbow{{{"stable_neo_hookean", 13.7, 5860, 25.6},
                                                              {"stvk_kikuuwe", 32.0, 14446, 140.3}}};
inline constexpr long kPaperElbowHexes = 45809;

// Arm dimensions in metres; the arm lies along +x, shoulder at x = 0, elbow at x = kElbowX,
// anterior (biceps) side +z, elbow axis along y.
inline constexpr double kElbowX = 0.30;
inline constexpr double kWristX = 0.56;

SignedDistance arm_sdf();
// A box that holds the arm.
Eigen::AlignedBox3d arm_bounds();
// The arm's hexahedral lattice with cell size h; the lattice planes y = 0 and z = 0 pass
// through the bone axes so that every resolution binds vertices around them.
VolumeMesh arm_lattice(double h);
// The same from a closed arm surface (examples/meshes/arm.obj): voxelize_surface with the grid
// planes through the origin, so again y = 0 and z = 0 are lattice planes.
VolumeMesh arm_lattice(const TriangleSurface& arm, double h);

// Humerus (never moves) and radius/ulna (rigid, keyed at frames 0 and `frames`, turned by
// `degrees` about the elbow axis; slerp between).
// `bone_radius` must exceed the lattice's cell size so that each bone binds a ring of vertices
// around its axis (one line of vertices would leave the flesh free to spin about it).
Rig elbow_rig(int frames, double degrees = 120.0, double bone_radius = 0.016);

struct ElbowConfig {
  // The arm surface to voxelise (examples/meshes/arm.obj); empty: arm_sdf(). With a surface
  // the bulges are measured on its embedded vertices, otherwise on the lattice's boundary.
  std::filesystem::path arm_surface;
  std::string family = "stable_neo_hookean";
  double E = 1e5;
  double nu = 0.45;
  std::map<std::string, double> parameters;  // non-normalised material parameters (e.g. kappa)
  double cell_size = 0.0125;
  double bone_radius = 0.016;
  double degrees = 120.0;
  int frames = 6;
  bool self_contact = true;
  double contact_stiffness = 0.0;  // Pa/m; 0 picks 50 E / cell_size
  bool refine_contact = false;
  SolverSpec solver = paper_solver();
};

struct ElbowFrame {
  ExperimentFrame solve;  // iterations, volume, timings
  int contacts = 0;       // penetrating samples at the end of the frame
  double max_depth = 0.0;
  // Max radial growth (m) of surface vertices about the bone axis, over the biceps belly
  // (rest x in [0.04, 0.24]) and the forearm belly (rest x in [0.36, 0.52]): the embedded arm
  // surface's vertices, or the lattice's free boundary vertices without a surface.
  double biceps_bulge = 0.0, forearm_bulge = 0.0;
  double gap = 0.0;  // smallest distance between biceps-side and forearm-side surface samples
};

struct ElbowRun {
  Eigen::Index vertices = 0, elements = 0, samples = 0, bound_vertices = 0;
  double rest_volume = 0.0;
  double cell_size = 0.0;
  std::vector<ElbowFrame> frames;
  Eigen::VectorXd x;

  double volume_change_percent() const;
  double biceps_bulge() const { return frames.back().biceps_bulge; }
  double forearm_bulge() const { return frames.back().forearm_bulge; }
  // Biceps and forearm touch (gap below half a cell, or cross-region contacts active).
  bool in_contact() const;
  // Some sample is deeper than a quarter cell inside the body after the solve.
  bool interpenetrating() const;
  double mean_newton() const;
  double mean_linear() const;
  double mean_seconds() const;
};

ElbowRun run_elbow(const ElbowConfig& config,
                   const std::function<void(const ElbowFrame&)>& on_frame = {});

}  // namespace sinew
