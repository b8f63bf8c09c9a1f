#pragma once
// A scene file (JSON, docs/scene-format.md): mesh or shape, material, boundary conditions,
// loads, solver settings, frames and outputs. load_scene validates every field and names the
// file, JSON path and reason of the first problem.
#include <filesystem>
#include <array>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "sinew/integrator/load_step_predictor.hpp"
#include "sinew/motion/prescribed_motion.hpp"
#include "sinew/model/dynamics_spec.hpp"
#include "sinew/material/spec.hpp"
#include "sinew/mesh/selection.hpp"
#include "sinew/mesh/volume_mesh.hpp"
#include "sinew/model/scene_constraints.hpp"
#include "sinew/model/surface_sources.hpp"
#include "sinew/solver/linear_solver.hpp"
#include "sinew/solver/newton.hpp"

namespace sinew {

struct Rig;                  // sinew/motion/rig.hpp
struct SelfContactSettings;  // sinew/forms/self_contact_form.hpp

struct BoxShape {
  Eigen::Vector3d lo, hi;
};
struct CylinderShape {
  Eigen::Vector3d center;
  double radius = 0.0, length = 0.0;
  int axis = 0;
};
struct SphereShape {
  Eigen::Vector3d center;
  double radius = 0.0;
};
// Voxel occupancy: dims cells over [lo, hi], occupancy in x-fastest order.
struct VoxelShape {
  Eigen::Vector3d lo, hi;
  Eigen::Vector3i dims;
  std::vector<int> occupancy;
};
struct MeshFile {
  std::filesystem::path path;  // resolved against the scene's folder
  bool reorient = false;       // renumber inverted elements instead of rejecting them
};

struct MeshSpec {
  std::variant<BoxShape, CylinderShape, SphereShape, VoxelShape, MeshFile, SurfaceVoxels, SurfaceTetrahedra> source;
  // Lattice resolution: explicit cell counts (box), or a cell size, or the number of cells
  // along the longest side of the shape's bounding box.
  std::optional<Eigen::Vector3i> cells;
  std::optional<double> cell_size;
  std::optional<int> resolution;
  ElementKind element = ElementKind::Hex8;  // lattices only: "tet" splits each hex into six
  // A closed surface bound to the mesh and written deformed every frame (scene_surface.hpp).
  std::optional<std::filesystem::path> embed;
};

struct BoundarySpec {
  std::string name;
  VertexSelector select;
  RigidMotion motion;
  std::array<bool, 3> components{true, true, true};  // prescribed coordinates ("components")
  std::optional<Eigen::Vector3d> direction;          // unit; only the motion along it is prescribed
};

// Every load is multiplied by its amplitude at the frame (load control; default: constant 1).
struct PointLoad {
  VertexSelector select;
  Eigen::Vector3d force;  // per selected vertex
  Amplitude amplitude;
};
struct Traction {
  VertexSelector select;  // boundary faces whose vertices are all selected
  Eigen::Vector3d traction;  // force per unit rest area
  Amplitude amplitude;
};

struct PressureLoad {
  VertexSelector select;  // boundary faces whose vertices are all selected
  double pressure = 0.0;  // force per current area, against the current outward normal (follower)
  Amplitude amplitude;
};

struct SolverSpec {
  NewtonSettings newton;
  LinearSolverSettings linear;
  Projection projection = Projection::Clamp;
  LoadStepPredictor predictor = LoadStepPredictor::Auto;  // quasistatic: where each load step starts
};

struct OutputSpec {
  bool vtu = true;
  bool obj = true;
  int every = 1;
  bool selections = false;  // write selections.json (run/selection_output.hpp)
};

struct Scene {
  std::filesystem::path file;  // where it was loaded from
  std::string text;            // the parsed JSON, dumped: what identifies a scene built in memory
  std::string description;     // free text, echoed to summary.json
  MeshSpec mesh;
  MaterialSpec material;
  double density = 1000.0;
  std::vector<BoundarySpec> boundary;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  Amplitude gravity_amplitude;
  std::vector<PointLoad> point_loads;
  std::vector<Traction> tractions;
  std::vector<PressureLoad> pressures;
  Eigen::Vector3d body_force = Eigen::Vector3d::Zero();  // force per unit rest volume
  Amplitude body_force_amplitude;
  SolverSpec solver;
  int frames = 1;
  OutputSpec output;
  std::optional<ConstraintsSpec> constraints;  // dynamics with paper 001 constraints (docs/energy-limits.md)
  std::optional<DynamicsSpec> dynamics;  // absent: quasistatic load stepping
  std::vector<ObstacleSpec> obstacles;
  std::shared_ptr<const Rig> rig;                           // "rig" (scene_rig.hpp)
  std::shared_ptr<const SelfContactSettings> self_contact;  // "self_contact" (scene_rig.hpp)
};

// The most frames a scene (or `sinew run --frames`) may ask for.
constexpr int kMaxFrames = 1000000;

Scene load_scene(const std::filesystem::path& file);
// A boundary or obstacle motion in the scene's JSON form ({"type": "translate", "per_frame": [0,
// 0, 1]}), checked as the scene reader checks it; errors name `context` and the field.
RigidMotion motion_from_json(const nlohmann::json& json, const std::string& context);
Scene parse_scene(const nlohmann::json& json, const std::filesystem::path& file);

// Every file the scene reads besides itself, resolved: the mesh file, the surface a mesh is
// made from, the embedded surface, the rig file and bone meshes. A checkpoint fingerprints
// them, so --resume notices when one changed.
std::vector<std::filesystem::path> scene_input_files(const Scene& scene);

// The mesh the scene describes (lattice generated or file read), validated.
VolumeMesh build_scene_mesh(const Scene& scene);

}  // namespace sinew
