#include "experiments/elbow_experiment.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "sinew/core/error.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/element/embedding.hpp"
#include "sinew/io/surface_reader.hpp"
#include "sinew/mesh/inside_test.hpp"
#include "sinew/mesh/voxelize.hpp"
#include "sinew/material/spec.hpp"
#include "sinew/forms/bone_spring_form.hpp"
#include "sinew/solver/newton.hpp"

namespace sinew {
namespace {

// Polynomial smooth minimum (blend width k): rounds the joins between the arm's parts.
double smooth_min(double a, double b, double k) {
  const double h = std::clamp(0.5 + 0.5 * (b - a) / k, 0.0, 1.0);
  return b + (a - b) * h - k * h * (1.0 - h);
}

// A capsule whose radius goes linearly from ra at a to rb at b (distance bound, exact on the
// axis-normal cross sections).
double tapered_capsule(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double ra, double rb) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm() - (ra + t * (rb - ra));
}

// Ellipsoid distance bound (|p/r| (|p/r| - 1) / |p/r^2|).
double ellipsoid(const Eigen::Vector3d& p, const Eigen::Vector3d& c, const Eigen::Vector3d& r) {
  const Eigen::Vector3d q = p - c;
  const double k0 = q.cwiseQuotient(r).norm();
  const double k1 = q.cwiseQuotient(r.cwiseProduct(r)).norm();
  if (k1 == 0.0) return -r.minCoeff();
  return k0 * (k0 - 1.0) / k1;
}

const Eigen::Vector3d kElbowCentre(kElbowX, 0.0, 0.0);
const Eigen::Vector3d kElbowAxis(0.0, -1.0, 0.0);  // positive angles turn the forearm towards +z

double point_line_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& o, const Eigen::Vector3d& dir) {
  const Eigen::Vector3d d = p - o;
  return (d - d.dot(dir) * dir).norm();
}

}  // namespace

SignedDistance arm_sdf() {
  // Keep in step with scripts/make_arm_mesh.py (same parts and numbers).
  return [](const Eigen::Vector3d& p) {
    const double upper = tapered_capsule(p, Eigen::Vector3d(0, 0, 0), kElbowCentre, 0.044, 0.040);
    const double biceps = ellipsoid(p, Eigen::Vector3d(0.15, 0.0, 0.024), Eigen::Vector3d(0.10, 0.034, 0.036));
    const double fore = tapered_capsule(p, kElbowCentre, Eigen::Vector3d(kWristX, 0, 0), 0.040, 0.026);
    const double flexors = ellipsoid(p, Eigen::Vector3d(0.37, 0.0, 0.012), Eigen::Vector3d(0.08, 0.036, 0.030));
    double d = smooth_min(upper, biceps, 0.012);
    d = smooth_min(d, fore, 0.012);
    return smooth_min(d, flexors, 0.012);
  };
}

Eigen::AlignedBox3d arm_bounds() {
  return Eigen::AlignedBox3d(Eigen::Vector3d(-0.05, -0.06, -0.06), Eigen::Vector3d(0.59, 0.06, 0.07));
}

VolumeMesh arm_lattice(double h) {
  if (!(std::isfinite(h) && h > 0.0 && h < 0.1)) throw Error("cell size must be in (0, 0.1) m", "arm lattice");
  // Grid planes at integer multiples of h, so y = 0 and z = 0 (the bone axes) are planes.
  const Eigen::AlignedBox3d b = arm_bounds();
  const Eigen::Vector3d lo = (b.min() / h).array().floor() * h;
  const Eigen::Vector3d hi = (b.max() / h).array().ceil() * h;
  const Eigen::Vector3i cells = ((hi - lo) / h).array().round().cast<int>();
  const SignedDistance sdf = arm_sdf();
  return occupancy_lattice(Eigen::AlignedBox3d(lo, hi), cells, [&](const Eigen::Vector3d& p) { return sdf(p) <= 0.0; });
}

VolumeMesh arm_lattice(const TriangleSurface& arm, double h) {
  if (!(std::isfinite(h) && h > 0.0 && h < 0.1)) throw Error("cell size must be in (0, 0.1) m", "arm lattice");
  VoxelizeOptions options;
  options.cell_size = h;
  options.grid_origin = Eigen::Vector3d::Zero();
  return voxelize_surface(InsideTest(arm), options);
}

Rig elbow_rig(int frames, double degrees, double bone_radius) {
  if (frames < 1) throw Error("frames must be at least 1", "elbow rig");
  Rig rig;
  Bone humerus;
  humerus.name = "humerus";
  // Both bones end kBoneJointClearance short of the elbow axis (header: why).
  humerus.shape = std::make_shared<CapsuleShape>(Eigen::Vector3d(-0.02, 0, 0), Eigen::Vector3d(kElbowX - kBoneJointClearance, 0, 0), bone_radius);
  humerus.keys.push_back(BoneKey{});
  Bone forearm;
  forearm.name = "radius_ulna";
  forearm.shape = std::make_shared<CapsuleShape>(Eigen::Vector3d(kElbowX + kBoneJointClearance, 0, 0), Eigen::Vector3d(0.55, 0, 0), bone_radius);
  // One key per frame, each an exact turn about the elbow axis through its centre (the pivot).
  for (int k = 0; k <= frames; ++k) {
    BoneKey key;
    key.frame = k;
    key.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(degrees * k / frames * std::numbers::pi / 180.0, kElbowAxis));
    key.center = kElbowCentre;
    forearm.keys.push_back(key);
  }
  rig.bones = {humerus, forearm};
  validate_rig(rig, "elbow rig");
  return rig;
}

double ElbowRun::volume_change_percent() const {
  if (frames.empty()) throw Error("no frame was run", "elbow experiment");
  return 100.0 * (frames.back().solve.volume / rest_volume - 1.0);
}
bool ElbowRun::in_contact() const { return !frames.empty() && frames.back().gap < 0.5 * cell_size; }
bool ElbowRun::all_converged() const {
  return !frames.empty() && std::all_of(frames.begin(), frames.end(), [](const ElbowFrame& f) { return f.solve.converged; });
}
bool ElbowRun::interpenetrating() const { return !frames.empty() && frames.back().max_depth > 0.25 * cell_size; }
double ElbowRun::mean_newton() const {
  double s = 0.0;
  for (const auto& f : frames) s += f.solve.newton_iterations;
  return s / std::max<size_t>(1, frames.size());
}
double ElbowRun::mean_linear() const {
  double s = 0.0;
  for (const auto& f : frames) s += f.solve.linear_iterations;
  return s / std::max<size_t>(1, frames.size());
}
double ElbowRun::mean_seconds() const {
  double s = 0.0;
  for (const auto& f : frames) s += f.solve.seconds;
  return s / std::max<size_t>(1, frames.size());
}

ElbowRun run_elbow(const ElbowConfig& c, const std::function<void(const ElbowFrame&)>& on_frame) {
  const std::string where = "elbow experiment";
  if (c.frames < 1) throw Error("frames must be at least 1", where);
  std::optional<TriangleSurface> arm;
  if (!c.arm_surface.empty()) arm = read_triangle_surface(c.arm_surface);
  auto disc = std::make_shared<Discretization>(arm ? arm_lattice(*arm, c.cell_size) : arm_lattice(c.cell_size), where);
  const VolumeMesh& mesh = disc->mesh();
  MaterialSpec material;
  material.family = c.family;
  material.target = YoungPoisson{c.E, c.nu};
  material.parameters.values = c.parameters;
  Problem problem(mesh.num_vertices());
  problem.add_form(std::make_shared<ElasticForm>(disc, build_material(material), c.solver.projection));
  SelfContactSettings contact;
  // Default penalty: 50 E per cell of penetration, stiff against the flesh yet well conditioned.
  contact.stiffness = c.contact_stiffness > 0.0 ? c.contact_stiffness : 50.0 * c.E / c.cell_size;
  contact.refine = c.refine_contact;
  auto contact_form = std::make_shared<SelfContactForm>(mesh, contact);
  if (c.self_contact) problem.add_form(contact_form);

  if (c.substeps < 1) throw Error("substeps must be at least 1", where);
  if (!(c.joint_exclusion >= 0.0 && c.joint_exclusion < 0.1)) throw Error("joint_exclusion must be in [0, 0.1) m", where);
  // The rig is keyed in flexion increments; frame f ends at increment f * substeps.
  const int increments = c.frames * c.substeps;
  const Rig rig = elbow_rig(increments, c.degrees, c.bone_radius);
  const RigBinding binding = bind_rig(rig, mesh.vertices);
  for (size_t b = 0; b < rig.bones.size(); ++b)
    if (binding.count_per_bone[b] == 0) throw Error("bone " + rig.bones[b].name + " binds no lattice vertex", where);
  auto linear = make_linear_solver(c.solver.linear);

  ElbowRun run;
  run.vertices = mesh.num_vertices();
  run.elements = mesh.num_elements();
  run.samples = static_cast<Eigen::Index>(contact_form->samples().size());
  run.bound_vertices = static_cast<Eigen::Index>(binding.bound_vertices.size());
  run.cell_size = c.cell_size;
  run.substeps = c.substeps;
  for (Eigen::Index e = 0; e < disc->num_elements(); ++e) run.rest_volume += disc->rest_volume(e);

  // Lattice surface samples on either side, away from the elbow's own flesh, for the gap.
  const std::vector<int>& samples = contact_form->samples();
  std::vector<int> far_upper, far_fore;
  for (int s : samples) {
    const double X = mesh.vertices(s, 0);
    if (X < kElbowX - 0.06) far_upper.push_back(s);
    if (X > kElbowX + 0.06) far_fore.push_back(s);
  }
  auto gap_at = [&](const Eigen::VectorXd& y) {
    double gap = std::numeric_limits<double>::infinity();
    for (int a : far_upper)
      for (int b : far_fore) gap = std::min(gap, (y.segment<3>(3 * a) - y.segment<3>(3 * b)).norm());
    return gap;
  };
  run.rest_gap = gap_at(mesh.rest_positions());
  // Bulge probes: rest points and how to follow them.
  Eigen::MatrixX3d probe_rest;
  std::optional<Embedding> probe_embedding;
  if (arm) {
    probe_rest = arm->vertices;
    probe_embedding = embed_points(mesh, probe_rest);
  } else {
    std::vector<int> free_samples;
    for (int s : samples)
      if (binding.bone[s] < 0) free_samples.push_back(s);
    probe_rest.resize(static_cast<Eigen::Index>(free_samples.size()), 3);
    for (size_t i = 0; i < free_samples.size(); ++i) probe_rest.row(static_cast<Eigen::Index>(i)) = mesh.vertices.row(free_samples[i]);
    // The lattice vertices themselves: a one-node "embedding".
    Embedding e;
    e.nodes.resize(probe_rest.rows(), 1);
    e.weights = Eigen::MatrixXd::Ones(probe_rest.rows(), 1);
    for (size_t i = 0; i < free_samples.size(); ++i) e.nodes(static_cast<Eigen::Index>(i), 0) = free_samples[i];
    e.element.assign(free_samples.size(), -1);
    probe_embedding = std::move(e);
  }
  // Each segment's probes, the elbow crease included; only the few mm at the joint plane (where
  // the fold turns the flesh about the elbow axis) and the shoulder and wrist caps are left out.
  std::vector<int> upper_probes, fore_probes;
  for (Eigen::Index p = 0; p < probe_rest.rows(); ++p) {
    const double X = probe_rest(p, 0);
    if (X >= 0.0 && X <= kElbowX - c.joint_exclusion) upper_probes.push_back(static_cast<int>(p));
    if (X >= kElbowX + c.joint_exclusion && X <= kWristX) fore_probes.push_back(static_cast<int>(p));
  }

  Eigen::VectorXd x = mesh.rest_positions();
  for (int frame = 1; frame <= c.frames; ++frame) {
    const auto t0 = std::chrono::steady_clock::now();
    ElbowFrame f;
    f.solve.frame = frame;
    f.solve.converged = true;
    for (int sub = 1; sub <= c.substeps; ++sub) {
      const int increment = (frame - 1) * c.substeps + sub;
      std::vector<char> fixed(x.size(), 0);
      apply_rig(rig, binding, mesh.vertices, increment, x, fixed);
      problem.set_fixed(fixed);
      const NewtonReport r = newton_solve(problem, x, *linear, c.solver.newton);
      // As in run_experiment: a failed solve is recorded and the next increment starts from its
      // best effort (never hidden, never retried with other settings).
      f.solve.converged = f.solve.converged && r.converged;
      f.solve.newton_iterations += r.iterations;
      f.solve.linear_iterations += r.linear_iterations;
      f.solve.residual = r.residual;
      f.solve.energy = r.energy;
      f.solve.assembly_seconds += r.assembly_seconds;
      f.solve.solve_seconds += r.solve_seconds;
      if (!r.converged && f.solve.failure.empty()) f.solve.failure = "increment " + std::to_string(sub) + ": " + r.failure;
      f.substeps += r.converged ? 1 : 0;
    }
    f.solve.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (Eigen::Index e = 0; e < disc->num_elements(); ++e)
      for (int q = 0; q < disc->quadrature_points(); ++q)
        f.solve.volume += disc->weight(e, q) * disc->deformation_gradient(e, q, x).determinant();
    f.solve.min_quadrature_J = min_quadrature_J(*disc, x);
    f.volume_change_percent = 100.0 * (f.solve.volume / run.rest_volume - 1.0);

    // Penetration after the solve (whether or not contact was on).
    const std::vector<SurfaceContact> contacts = contact_form->detect(x);
    f.contacts = static_cast<int>(contacts.size());
    for (const auto& k : contacts) {
      f.max_surface_depth = std::max(f.max_surface_depth, contact_form->surface_depth(x, k.sample));
      if (k.depth > f.max_depth) {
        f.max_depth = k.depth;
        f.deepest_rest = mesh.vertices.row(k.sample).transpose();
      }
    }
    f.contacts_active = c.self_contact ? static_cast<int>(contact_form->contacts().size()) : 0;

    // Radial growth about each segment's deformed bone axis line.
    const Affine34 A = rig.bones[1].transform_at(frame * c.substeps);
    const Eigen::Vector3d fore_dir = A.leftCols<3>() * Eigen::Vector3d::UnitX();
    const Eigen::MatrixX3d probes = probe_embedding->positions(x);
    auto growth = [&](int p, const Eigen::Vector3d& o, const Eigen::Vector3d& dir) {
      const Eigen::Vector3d X = probe_rest.row(p).transpose();
      return point_line_distance(probes.row(p).transpose(), o, dir) -
             point_line_distance(X, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX());
    };
    f.biceps_bulge = -std::numeric_limits<double>::infinity();
    f.forearm_bulge = -std::numeric_limits<double>::infinity();
    for (int p : upper_probes) f.biceps_bulge = std::max(f.biceps_bulge, growth(p, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()));
    for (int p : fore_probes) f.forearm_bulge = std::max(f.forearm_bulge, growth(p, A.leftCols<3>() * kElbowCentre + A.col(3), fore_dir));
    f.gap = gap_at(x);
    run.frames.push_back(f);
    if (on_frame) on_frame(run.frames.back());
  }
  run.x = std::move(x);
  return run;
}

}  // namespace sinew
