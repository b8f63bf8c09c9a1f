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

#include "sinew/forms/self_contact_form.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/triangle_surface.hpp"
#include "sinew/motion/rig.hpp"
#include "experiments/paper000_experiments.hpp"

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

// Both bones end this far (m) from the elbow axis. A coarse lattice needs bones thicker than its
// cells (a ring of bound vertices around each axis); at 120 degrees of flexion the forearm bone
// sits d sin(120 deg) from the humerus axis at distance d from the joint, so bones reaching
// within 6 cm of the joint leave (52 mm - two bone radii) for the 10 cm of biceps and forearm
// flesh between them: the bound rings drive the crease flesh through itself whatever the
// material or contact stiffness. Ending 10 cm off the joint leaves the crease flesh room to
// bulge and to meet (measured at h = 20 mm, nu = 0.488: about 6 mm deep instead of 30 mm).
inline constexpr double kBoneJointClearance = 0.10;

SignedDistance arm_sdf();
// A box that holds the arm.
Eigen::AlignedBox3d arm_bounds();
// The arm's hexahedral lattice with cell size h; the lattice planes y = 0 and z = 0 pass
// through the bone axes so that every resolution binds vertices around them.
VolumeMesh arm_lattice(double h);
// The same from a closed arm surface (examples/meshes/arm.obj): voxelize_surface with the grid
// planes through the origin, so again y = 0 and z = 0 are lattice planes.
VolumeMesh arm_lattice(const TriangleSurface& arm, double h);

// Humerus (never moves) and radius/ulna (rigid, turned by `degrees` about the elbow axis over
// `frames`, keyed at every frame so that each frame is an exact turn about the joint).
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
  // Flexion increments per frame: each is solved to convergence and self-contact detects new
  // penetrating samples at every converged increment, so the crease closes in smaller steps.
  // (Measured: at h = 10 mm, nu = 0.45, 3 increments per frame did not change how deep the
  // crease's fold ends up; docs/experiments.md, Elbow flexion.)
  int substeps = 1;
  // Bulge probes within this distance (m) of the elbow plane (rest x = kElbowX) are skipped:
  // right at the joint axis the fold turns the flesh about the axis and its distance from
  // either bone's axis line means nothing.
  double joint_exclusion = 0.005;
  bool self_contact = true;
  double contact_stiffness = 0.0;  // Pa/m; 0 picks 50 E / cell_size
  bool refine_contact = false;
  SolverSpec solver = paper_solver();
};

struct ElbowFrame {
  ExperimentFrame solve;  // iterations (summed over the substeps), volume, timings
  int substeps = 0;       // converged flexion increments in this frame
  int contacts = 0;       // penetrating samples at the end of the frame
  // Deepest penetrating sample: distance to its reference-map target (SurfaceContact::depth,
  // what "interpenetrating" is judged on), and, as a check, the largest distance of a
  // penetrating sample to the nearest deformed surface outside its own neighbourhood
  // (SelfContactForm::surface_depth).
  double max_depth = 0.0;
  double max_surface_depth = 0.0;
  Eigen::Vector3d deepest_rest = Eigen::Vector3d::Zero();  // rest position of the deepest sample
  // Max radial growth (m) of surface vertices about their segment's deformed bone axis line
  // (distance now minus distance at rest): upper arm (biceps side) = rest x in
  // [0, kElbowX - joint_exclusion], forearm = rest x in [kElbowX + joint_exclusion, kWristX];
  // the elbow crease is included, the end caps are not. Probes: the embedded arm surface's
  // vertices, or the lattice's free boundary vertices without a surface.
  double biceps_bulge = 0.0, forearm_bulge = 0.0;
  // Smallest distance between lattice surface samples of the upper arm (rest x < kElbowX - 0.06)
  // and of the forearm (rest x > kElbowX + 0.06): the biceps-forearm gap, away from the
  // elbow's own flesh (which joins the two sides and is never "apart").
  double gap = 0.0;
  int contacts_active = 0;  // contacts in the self-contact form after the frame
  double volume_change_percent = 0.0;
};

struct ElbowRun {
  Eigen::Index vertices = 0, elements = 0, samples = 0, bound_vertices = 0;
  int substeps = 1;  // flexion increments per frame
  double rest_volume = 0.0;
  double rest_gap = 0.0;  // ElbowFrame::gap of the straight arm
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
  bool all_converged() const;
  double mean_newton() const;
  double mean_linear() const;
  double mean_seconds() const;
};

ElbowRun run_elbow(const ElbowConfig& config,
                   const std::function<void(const ElbowFrame&)>& on_frame = {});

}  // namespace sinew
