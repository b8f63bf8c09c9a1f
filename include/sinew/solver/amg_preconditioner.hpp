#pragma once
// Algebraic multigrid for any mesh ("amg"): one V-cycle of hypre's BoomerAMG per application,
// built from the assembled matrix alone, so it works on tetrahedra, meshes read from files and
// lattices alike (geometric "multigrid" needs a lattice grid). Systems AMG with 3 unknowns per
// vertex (x, y, z interleaved; only like unknowns couple in the hierarchy), HMIS coarsening,
// extended+i interpolation truncated to 4 entries per row, and l1-scaled symmetric Gauss-Seidel
// before and after each coarse correction (the same sweep), so the V-cycle is symmetric and
// serves as CG's preconditioner.
//
// hypre's elasticity options (nodal coarsening, the rigid-body rotations as interpolation
// vectors, as MFEM sets them) are settings: on the nu = 0.49 tetrahedral bars of the tests they
// saved no CG iterations (34 against 32 at 6,144 tetrahedra) and multiplied the hierarchy's size
// (operator complexity 13-24 against 2.4-3.1) and its setup time, so they are off by default.
//
// Each setup (each Newton matrix) copies the matrix into hypre and builds a new hierarchy:
// BoomerAMG has no numeric-only refresh. Fixed DOFs need nothing special: their rows and
// columns are the identity, decoupled unknowns AMG leaves on the finest level.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "sinew/solver/preconditioner.hpp"

namespace sinew {

// hypre's numbering for the choices (HYPRE_parcsr_ls.h).
struct AmgSettings {
  double strong_threshold = 0.5;  // hypre's advice for 3D problems (0.25 is for 2D)
  int coarsen_type = 10;          // 10 HMIS, 8 PMIS, 6 Falgout
  int aggressive_levels = 0;      // levels coarsened aggressively (cheaper, weaker)
  int interp_type = 6;            // 6 extended+i
  int max_interp_elements = 4;    // per row of P (truncation)
  int relax_type = 8;             // 8 l1-scaled symmetric Gauss-Seidel, 16 Chebyshev
  int sweeps = 1;                 // smoothing sweeps before and after each coarse correction
  int nodal = 0;                  // coarsen per vertex, strength from its blocks' norms: 0 off, 1 Frobenius, 4 row sum
  bool rigid_body_modes = false;  // with nodal > 0 and the mesh: rotations as interpolation vectors (GM-2)
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
