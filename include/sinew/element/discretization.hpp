#pragma once
// Precomputed element kinematics of a mesh: at each quadrature point the rest-space
// shape-function gradients dN/dX and the quadrature weight times the rest Jacobian, so that
// F = x_e D and dF/dx is a fixed linear map (paper 001 §3.2).
#include <Eigen/Core>
#include <vector>

#include "sinew/core/types.hpp"
#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

class Discretization {
 public:
  explicit Discretization(VolumeMesh mesh, const std::string& source = "mesh");

  const VolumeMesh& mesh() const { return mesh_; }
  int nodes() const { return nodes_; }
  int quadrature_points() const { return qpoints_; }
  Eigen::Index num_elements() const { return mesh_.num_elements(); }
  Eigen::Index num_dofs() const { return 3 * mesh_.num_vertices(); }

  // dN/dX (nodes x 3) and weight (w * det dX/dxi) of quadrature point q of element e.
  const Eigen::MatrixX3d& gradients(Eigen::Index e, int q) const { return dN_dX_[point(e, q)]; }
  double weight(Eigen::Index e, int q) const { return weight_[point(e, q)]; }
  // Elements whose rest shapes are equal (edge vectors equal to 1e-12 of the element's size,
  // e.g. every cell of a lattice) share one set of gradients and weights: the number of
  // distinct sets kept.
  Eigen::Index num_rest_shapes() const { return static_cast<Eigen::Index>(weight_.size()) / qpoints_; }
  // Index of element e's rest shape among the num_rest_shapes() sets.
  int rest_shape(Eigen::Index e) const { return shape_[static_cast<size_t>(e)]; }
  double rest_volume(Eigen::Index e) const;

  // Node positions of element e from the DOF vector x (3 x nodes).
  Eigen::Matrix3Xd element_positions(Eigen::Index e, const Eigen::VectorXd& x) const;
  // F = x_e dN/dX.
  Mat3 deformation_gradient(Eigen::Index e, int q, const Eigen::VectorXd& x) const;

  // Elements grouped so that no two elements of a group share a vertex: scattering one
  // group's element contributions in parallel is race-free and deterministic.
  const std::vector<std::vector<Eigen::Index>>& color_groups() const { return colors_; }

  // Runs of consecutive elements (first, end), coloured so that no two runs of one colour share
  // a vertex: a task takes a whole run in element order, so an element's matrix blocks are
  // still in cache when its neighbours in the run add to them (assembly streams the matrix about
  // once per colour; the element colouring above streams it once per element colour, 8 times on
  // a lattice).
  struct ElementRun {
    Eigen::Index first, end;
  };
  const std::vector<std::vector<ElementRun>>& run_colors() const { return run_colors_; }

 private:
  size_t point(Eigen::Index e, int q) const {
    return static_cast<size_t>(shape_[static_cast<size_t>(e)]) * static_cast<size_t>(qpoints_) + static_cast<size_t>(q);
  }
  VolumeMesh mesh_;
  int nodes_ = 0;
  int qpoints_ = 0;
  std::vector<int> shape_;  // rest-shape index of each element
  std::vector<Eigen::MatrixX3d> dN_dX_;  // per rest shape and quadrature point
  std::vector<double> weight_;
  std::vector<std::vector<Eigen::Index>> colors_;
  std::vector<std::vector<ElementRun>> run_colors_;
};

// Element gradient contribution of one quadrature point: w * vec-scatter of P D^T (3 x nodes).
// Element Hessian contribution: K(3a+i, 3b+j) += w sum_kl D(a,k) H(3k+i, 3l+j) D(b,l).
void add_element_hessian(const Eigen::MatrixX3d& D, const Mat9& H, double w, Eigen::MatrixXd& K);

}  // namespace sinew
