#pragma once
// Interpolation of a vector on coarse vertices to fine vertices (multigrid prolongation): fine
// vertex v takes sum_k weight[k] x[coarse[k]] over k in [offsets[v], offsets[v + 1]), the same
// weight for its three DOFs. Restriction is the transpose. A DOF mask ("free", one flag per
// fine DOF) drops fixed fine DOFs from both, so coarse corrections never move them.
#include <Eigen/Core>
#include <span>
#include <vector>

namespace sinew {

struct VertexInterpolation {
  Eigen::Index coarse_vertices = 0;
  std::vector<int> offsets{0};  // per fine vertex, size fine_vertices() + 1
  std::vector<int> coarse;      // coarse vertex of each entry
  std::vector<double> weight;   // weight of each entry

  Eigen::Index fine_vertices() const { return static_cast<Eigen::Index>(offsets.size()) - 1; }

  // fine (+)= P coarse over the free fine DOFs (fixed ones set to zero when not adding).
  void prolong(const Eigen::VectorXd& coarse_x, std::span<const char> fine_free, Eigen::VectorXd& fine_x, bool add) const;
  // coarse = P^T fine, with fixed fine DOFs left out. Needs the transpose (transpose()).
  void restrict_to(const Eigen::VectorXd& fine_x, std::span<const char> fine_free, Eigen::VectorXd& coarse_x) const;
  // Which coarse DOFs interpolate at least one free fine DOF (the others are fixed on the
  // coarse level: their rows of the Galerkin operator are empty).
  std::vector<char> coarse_free(std::span<const char> fine_free) const;

  // The transpose (per coarse vertex its fine vertices and weights), built by prepare().
  void prepare();
  std::vector<int> t_offsets, t_fine;
  std::vector<double> t_weight;
};

}  // namespace sinew
