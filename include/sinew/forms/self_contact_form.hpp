#pragma once
// Reference-map penalty self-contact (paper 000 §6, after Hirota et al. 2001 and Irving et al.
// 2004). Every boundary vertex is a surface sample. Whenever a Newton solve has converged with
// its current contact set (Form::refresh):
//   1. a uniform spatial grid over the deformed tetrahedra (the Kuhn split of a hexahedral
//      lattice, or the mesh's own tetrahedra) finds samples inside a tetrahedron that shares no
//      vertex with the sample's own elements (the excluded neighbourhood: a transiently
//      inverted element next to a sample is not contact), i.e. samples that have entered the
//      body elsewhere;
//   2. the barycentric coordinates in that tetrahedron map the sample to rest space, where the
//      closest point on the rest boundary (a grid over the rest boundary triangles) is found;
//   3. that point's barycentric coordinates w in its boundary triangle map it back to deformed
//      space: the spring target t_s = sum_i w_i x_i. With `refine`, a local search over
//      neighbouring deformed boundary triangles moves t_s to a closer deformed-surface point
//      (the paper's optional local optimisation).
// Energy: E = sum_s k A_s / 2 min(0, n_s . (x_s - sum_i w_i x_i))^2, A_s the sample's share of
// rest boundary area (so k is a pressure per unit penetration depth, Pa/m, independent of the
// resolution) and n_s the outward unit surface normal at the target (vertex normals interpolated): a one-sided frictionless
// spring along the normal (C1; zero once the sample is back outside).
// New samples are added at converged states and existing contacts keep their triangle,
// weights and normal, so Newton minimises one fixed energy between finitely many additions
// (re-fitting every contact at every iteration made the residual stall) and never detects at
// the distorted iterates of a solve's start. Once contacts exist, samples that enter the body
// are also added after every accepted Newton step if they are still shallow (add_at_iterate;
// additions only): the new springs push their samples out and drag neighbours in, and a
// neighbour caught only at the next converged state had gone deep enough to be mapped to the far
// surface and pushed through (the coarse elbow's crease ended 33 mm deep on one of ten
// rounding-level perturbations; the h = 10 mm crease at nu = 0.45 15-30 mm deep). Contacts more
// than a quarter grid cell outside are dropped; at each solve's start (Form::begin_solve) the
// carried contacts still inside the body are refitted. (A spring on the full vector x_s - t_s also pulls tangentially wherever
// the two linear maps miss the deformed closest point, so only the normal part is used.)
// The target moves with its triangle's vertices, so the spring pushes both sides apart (action
// and reaction); E is convex with PSD Hessian k A_s [1, -w]^T [1, -w] (x) n n^T on penetrating
// samples. A changed contact set changes couplings(), and Problem rebuilds the Hessian
// pattern. Freezing the target position instead makes two-sided contact oscillate: each face
// jumps to the other's old position. The form is solver-agnostic: quasistatic and time-stepped
// solves both call it through Problem.
#include <memory>
#include <unordered_map>
#include <vector>

#include "sinew/forms/form.hpp"
#include "sinew/mesh/surface.hpp"
#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

struct SelfContactSettings {
  double stiffness = 1e7;  // Pa/m
  bool refine = false;
  int refine_iterations = 8;
};

struct SurfaceContact {
  int sample = -1;    // volume-mesh vertex index of the penetrating sample
  int tet = -1;       // tetrahedron (of the Kuhn split) that contains it
  int triangle = -1;  // boundary triangle of the target
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();  // of the triangle's vertices
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // deformed outward surface normal at the target
  Eigen::Vector3d target = Eigen::Vector3d::Zero();   // at detection
  double depth = 0.0;  // |x_s - t_s| at detection
};

// A uniform grid hashing integer cells to item lists.
class UniformGrid {
 public:
  explicit UniformGrid(double cell = 1.0) : cell_(cell) {}
  void clear() { cells_.clear(); }
  void insert(int item, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
  const std::vector<int>* at(const Eigen::Vector3i& c) const;
  Eigen::Vector3i cell_of(const Eigen::Vector3d& p) const;
  double cell_size() const { return cell_; }

 private:
  static long long key(const Eigen::Vector3i& c);
  double cell_;
  std::unordered_map<long long, std::vector<int>> cells_;
};

// Closest point of triangle abc to p, as barycentric weights (sum 1, all >= 0).
Eigen::Vector3d closest_point_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c);

class SelfContactForm final : public Form {
 public:
  SelfContactForm(const VolumeMesh& mesh, const SelfContactSettings& settings);
  std::string name() const override { return "self_contact"; }

  // Contacts at positions x (does not change the form's frozen state).
  std::vector<SurfaceContact> detect(const Eigen::VectorXd& x) const;
  // Start of a Newton solve: the carried contacts still penetrating are refitted; none added.
  bool begin_solve(const Eigen::VectorXd& x) override;
  // At a converged state: newly penetrating samples are added (true if any), separated
  // contacts dropped; the others are unchanged.
  bool refresh(const Eigen::VectorXd& x) override;
  // After an accepted Newton step, when contacts exist: newly penetrating samples at most a sixth
  // of a grid cell deep are added (deeper ones wait for the converged state).
  bool add_at_iterate(const Eigen::VectorXd& x) override;
  bool couplings_changed() const override { return couplings_changed_; }
  const std::vector<SurfaceContact>& contacts() const { return contacts_; }

  double value(const Eigen::VectorXd& x) const override;
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const override;
  void couplings(std::vector<std::vector<int>>& cliques) const override;

  // How far a penetrating sample is inside the body: its distance to the closest deformed
  // boundary triangle outside its own neighbourhood (no vertex in the sample's elements), i.e.
  // how far it must move to leave the body. SurfaceContact::depth is the distance to the
  // reference-map target instead, which in a tight fold can be far from the nearest surface.
  double surface_depth(const Eigen::VectorXd& x, int sample) const;

  const std::vector<int>& samples() const { return samples_; }
  double sample_area(int vertex) const { return area_[vertex]; }

 private:
  Eigen::Vector3d closest_rest_point(const Eigen::Vector3d& X, int sample, int& triangle) const;
  // Moves (triangle, weights) to a closer deformed-surface point of the sample.
  void refine_target(const Eigen::VectorXd& x, int sample, int& triangle, Eigen::Vector3d& weights) const;
  Eigen::Vector3d target(const Eigen::VectorXd& x, const SurfaceContact& c) const;
  Eigen::MatrixX3d vertex_normals(const Eigen::VectorXd& x) const;
  Eigen::Vector3d surface_normal(const Eigen::VectorXd& x, const Eigen::MatrixX3d& normals, const SurfaceContact& c) const;
  bool triangle_has(int triangle, int vertex) const;
  // Appends the samples detected inside the body at x that are not `known` and at most
  // max_depth deep, keeping `contacts` sorted by sample; true if any.
  bool add_new_samples(const Eigen::VectorXd& x, const std::vector<char>& known, double max_depth,
                       std::vector<SurfaceContact>& contacts) const;

  SelfContactSettings settings_;
  Eigen::MatrixX3d rest_;
  Eigen::MatrixXi tets_;       // rows of 4 vertex indices
  Eigen::MatrixXi triangles_;  // rest boundary triangles
  std::vector<int> samples_;   // boundary vertices
  std::vector<double> area_;   // rest boundary area per vertex (one third of each triangle)
  std::vector<std::vector<int>> vertex_triangles_;
  std::vector<std::vector<int>> sample_ring_;  // per vertex: sorted vertices of its elements
  double cell_ = 1.0;
  UniformGrid rest_triangle_grid_;
  Eigen::AlignedBox3d rest_bounds_;
  std::vector<SurfaceContact> contacts_;
  bool couplings_changed_ = false;
};

}  // namespace sinew
