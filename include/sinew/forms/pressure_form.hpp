#pragma once
// Follower pressure on boundary faces: a pressure p acting against the current (deformed) outward
// normal, f = -p n da, consistently integrated: node a of a face gets -p * integral of N_a n da
// over the current face (triangles exactly, bilinear quads by 2x2 Gauss points, also exact).
//
// Energy. On a closed surface the load is conservative, E = p (V(x) - V(X)) with V the volume
// the surface encloses, and its force is exactly -dE/dx. On an open surface the form's energy is
// p times the volume swept by the loaded faces from their rest position, closed along the
// surface's boundary edges by the ribbon between each edge's rest and current position. Its
// gradient is the follower force exactly where the ribbon exerts no force on a free DOF: at
// closed surfaces, at boundary edges whose vertices are fixed, and at boundary edges that stay
// in a plane their vertices are held to (rollers, symmetry planes, plane strain). Elsewhere (a
// loaded patch with free edges) the follower load has no potential; the form's gradient is still
// the exact follower force and its energy (which Newton's line search uses) differs from the
// force's work by the ribbons' share, zero at rest and growing with the edges' motion.
//
// Stiffness. The load stiffness dg/dx is not symmetric face by face; the form adds its symmetric
// part. Summed over a closed surface, or restricted to the free DOFs under the conditions above,
// the exact load stiffness is symmetric (it is the Hessian of the energy), so the symmetric part
// is exact there. It is not PSD in general (add_hessian does not project it).
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
  // `rest`: the rest positions of every vertex (x[3 v + i]).
  PressureForm(std::vector<std::vector<int>> faces, const Eigen::VectorXd& rest, double pressure);

  std::string name() const override { return "pressure"; }
  double value(const Eigen::VectorXd& x) const override;
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const override;
  void couplings(std::vector<std::vector<int>>& cliques) const override;
  // Exact (energy and force agree at every DOF) only for a closed surface.
  bool exact_derivatives() const override { return boundary_edges_.empty(); }

  double pressure() const { return pressure_; }
  double scale() const { return scale_; }
  void set_scale(double scale) { scale_ = scale; }
  const std::vector<std::vector<int>>& faces() const { return faces_; }
  // Edges used by one loaded face only (as (from, to) in that face's orientation); none for a
  // closed surface.
  const std::vector<std::array<int, 2>>& boundary_edges() const { return boundary_edges_; }
  // The follower force on every DOF, -gradient (total: sum over vertices).
  Eigen::VectorXd forces(const Eigen::VectorXd& x) const;

 private:
  double enclosed_volume(const Eigen::VectorXd& x) const;  // faces + ribbons, about origin_
  std::vector<std::vector<int>> faces_;
  std::vector<std::array<int, 2>> boundary_edges_;
  Eigen::VectorXd rest_;
  Eigen::Vector3d origin_;  // reference point of the volume integrals (for round-off only)
  double rest_volume_ = 0.0;
  double pressure_ = 0.0;
  double scale_ = 1.0;
};

}  // namespace sinew
