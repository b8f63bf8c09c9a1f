#pragma once
// Algebraic multigrid for any mesh ("amg"): one V-cycle of hypre's BoomerAMG per application,
// built from the assembled matrix alone, so it works on tetrahedra, meshes read from files and
// lattices alike (geometric "multigrid" needs a lattice grid). Elasticity settings after hypre's
// and MFEM's: systems AMG with 3 unknowns per vertex and nodal coarsening (a vertex is coarse or
// fine as a whole, by the norms of its 3x3 blocks), HMIS coarsening, extended+i interpolation
// and, when the mesh is known, the rigid-body rotations about the rest shape as interpolation
// vectors (GM-2), which the unknown-based interpolation cannot represent. Smoothing is
// l1-scaled symmetric Gauss-Seidel before and after each coarse correction (the same sweep),
// so the V-cycle is symmetric and serves as CG's preconditioner.
//
// Each setup (each Newton matrix) copies the matrix into hypre and builds a new hierarchy:
// BoomerAMG has no numeric-only refresh. Fixed DOFs need nothing special: their rows and
// columns are the identity, decoupled vertices AMG leaves on the finest level.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "sinew/solver/preconditioner.hpp"

namespace sinew {

// hypre's numbering for the choices (HYPRE_parcsr_ls.h); the defaults are the elasticity ones.
struct AmgSettings {
  double strong_threshold = 0.5;  // hypre's advice for 3D problems (0.25 is for 2D)
  int coarsen_type = 10;          // 10 HMIS, 8 PMIS, 6 Falgout
  int aggressive_levels = 0;      // levels coarsened aggressively (cheaper, weaker)
  int interp_type = 6;            // 6 extended+i
  int max_interp_elements = 4;    // per row of P (truncation)
  int relax_type = 8;             // 8 l1-scaled symmetric Gauss-Seidel, 16 Chebyshev
  int sweeps = 1;                 // smoothing sweeps before and after each coarse correction
  int nodal = 4;                  // strength between vertices: 0 off (per unknown), 1 Frobenius, 4 row sum
  bool rigid_body_modes = true;   // rotations as interpolation vectors (needs the mesh)
  int max_levels = 25;
};

class AmgPreconditioner final : public Preconditioner {
 public:
  explicit AmgPreconditioner(AmgSettings settings = {});
  ~AmgPreconditioner() override;
  AmgPreconditioner(const AmgPreconditioner&) = delete;
  AmgPreconditioner& operator=(const AmgPreconditioner&) = delete;
  std::string name() const override { return "amg"; }
  void setup(const LinearOperator& A, const SolverContext& context) override;
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) override;

  // After setup: the hierarchy's levels and the operator complexity (nonzeros of all levels
  // over those of the matrix), and whether rigid-body modes were used.
  int levels() const { return levels_; }
  double operator_complexity() const { return complexity_; }
  bool used_rigid_body_modes() const { return used_rbm_; }

 private:
  struct Hypre;  // hypre's objects (kept out of this header, which then needs no MPI)
  AmgSettings settings_;
  std::unique_ptr<Hypre> hypre_;
  int levels_ = 0;
  double complexity_ = 0.0;
  bool used_rbm_ = false;
};

}  // namespace sinew
