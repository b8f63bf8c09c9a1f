#pragma once
// Follower pressure on boundary faces: a pressure p acting against the current (deformed) outward
// normal, f = -p n da, consistently integrated: node a of a face gets -p * integral of N_a n da
// over the current face (triangles exactly, bilinear quads by 2x2 Gauss points, also exact).
//
// Energy. On a closed surface the load is conservative: E = p (V(x) - V(X)), V the volume the
// surface encloses, and the force is exactly -dE/dx. It is also conservative on the free DOFs of
// an open surface whose rim is held (its vertices fixed, or each rim edge kept in a plane its
// vertices are held to: rollers, symmetry planes, plane strain). A pressure on a patch with free
// edges has no potential. For open surfaces the form's energy is therefore minus the work its
// force does along a path: the straight segment from the last linearisation point x_l
// (linearize_at, every Newton iterate) to x, added to the energy at x_l. Each line search then
// sees the exact work of the follower force along its search line (so the Armijo test and the
// force residual agree), and where a potential exists this is that potential, path-independent.
// The segment's work is exact (the force is quadratic in x along it: 2-point Gauss).
//
// Stiffness. The load stiffness dg/dx is not symmetric face by face; the form adds its symmetric
// part. Summed over a closed surface, or on the free DOFs of a held rim, the exact load stiffness
// is symmetric (the energy's Hessian), so the symmetric part is exact there; for a patch with free
// edges it drops the antisymmetric part (Newton then converges linearly near the solution, not
// quadratically). It is not PSD in general (add_hessian does not project it).
//
// `scale` multiplies the pressure (a load ramp sets it per frame).
#include <array>
#include <vector>

#include "sinew/forms/form.hpp"

namespace sinew {

class PressureForm final : public Form {
 public:
  // `faces`: 3 (triangle) or 4 (bilinear quad, nodes in cyclic order) vertex indices each,
  // oriented outward (counter-clockwise seen from outside, as boundary_surface gives them);
  // `rest`: the rest positions of every vertex (x[3 v + i]), the start of the work path.
  PressureForm(std::vector<std::vector<int>> faces, const Eigen::VectorXd& rest, double pressure);

  std::string name() const override { return "pressure"; }
  double value(const Eigen::VectorXd& x) const override;
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const override;
  void couplings(std::vector<std::vector<int>>& cliques) const override;
  void linearize_at(const Eigen::VectorXd& x) override;
  bool begin_solve(const Eigen::VectorXd& x) override;
  // Energy and force agree at every DOF and state only for a closed surface.
  bool exact_derivatives() const override { return closed(); }

  double pressure() const { return pressure_; }
  double scale() const { return scale_; }
  void set_scale(double scale) { scale_ = scale; }
  const std::vector<std::vector<int>>& faces() const { return faces_; }
  // Edges used by one loaded face only (as (from, to) in that face's orientation): the rim of an
  // open surface; none for a closed one.
  const std::vector<std::array<int, 2>>& boundary_edges() const { return boundary_edges_; }
  bool closed() const { return boundary_edges_.empty(); }
  // The follower force on every DOF, -gradient.
  Eigen::VectorXd forces(const Eigen::VectorXd& x) const;

 private:
  double enclosed_volume(const Eigen::VectorXd& x) const;  // closed surfaces, about origin_
  std::vector<std::vector<int>> faces_;
  std::vector<std::array<int, 2>> boundary_edges_;
  Eigen::Vector3d origin_;  // reference point of the volume integral (round-off only)
  double rest_volume_ = 0.0;
  double pressure_ = 0.0;
  double scale_ = 1.0;
  // Open surfaces: the last linearisation point and the energy there.
  Eigen::VectorXd path_start_;
  double path_energy_ = 0.0;
};

}  // namespace sinew
