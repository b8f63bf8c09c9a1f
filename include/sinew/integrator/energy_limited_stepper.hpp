#pragma once
// One time step of paper 001 §5: linearised backward Euler A v* = b (Eq. 19) with
// A = M + h^2 K(x0), b = M v0 + h f(x0); the energy-limiting and contact constraints are
// evaluated at x* = x0 + h v*, linearised, and the LCP
//   0 <= lambda  perp  J A^-1 J^T lambda + C/h + J (v* - v_k) >= 0        (Eq. 23 at v_k = v*)
// is solved by projected Gauss-Seidel together with Coulomb friction; v = v* + A^-1 J^T lambda
// (Eq. 21). The linearisation is repeated at the new positions (SQP) until the nonlinear
// constraints hold within tolerance. From the second SQP iteration on, the quadratic model's
// matrix is the Lagrangian Hessian H = A + h sum_e (lambda_e / U_max) d2U_e/dx2: without the
// energy constraints' curvature the repeated linearisation can drift away from the limit
// instead of converging. A (and H) is factorised by CHOLMOD with the symbolic analysis reused,
// and one factorisation serves every column of H^-1 J^T.
//
// Factorisation reuse (the default): factorising A costs far more than everything else in a step
// (~15 ms at 1,900 DOFs against ~0.1 ms per triangular solve pair), and A = M + h^2 R K R^T
// changes slowly. So the factorisation of an earlier A (or H) is kept and used (a) to
// precondition CG for every solve with the current matrix, which stays exact to the CG tolerance,
// and (b) to form an approximate LCP matrix W~ = J P^-1 J^T. The LCP is then solved by a
// splitting iteration: PGS on W~ with q~ = w(lambda_i) - W~ lambda_i, where w(lambda_i) is the
// exact constraint velocity of the current multipliers; its fixed points solve the exact LCP. A
// refactorisation happens only when CG needs more than `max_cg_iterations` or the splitting
// does not converge, so the result is the same as with a fresh factorisation each time, up to
// the CG and PGS tolerances. On small meshes, where one factorisation costs fewer CG iterations
// than FactorizationReuse::exact_lagrangian_below, each Lagrangian Hessian H is factorised instead
// of lagged (A stays lagged): a lagged H would need CG solves and splitting sweeps every SQP
// iteration, which cost more there.
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "sinew/assembly/problem.hpp"
#include "sinew/constraints/contact_constraints.hpp"
#include "sinew/constraints/energy_limit.hpp"
#include "sinew/solver/lagged_factorization.hpp"
#include "sinew/solver/pgs.hpp"

namespace sinew {

struct EnergyLimitedStepSettings {
  double time_step = 0.01;
  std::optional<EnergyLimit> energy_limit;
  // Elements with U_e >= (1 - activation) U_max enter the LCP (the others cannot reach the
  // limit within one linearisation and would only cost PGS work).
  double activation = 0.1;
  PgsSettings pgs;
  int sqp_max_iterations = 20;
  double energy_tolerance = 1e-3;   // accept U_e <= (1 + tol) U_max
  double contact_tolerance = 1e-4;  // accept penetration up to this depth (m)
  // Where the previous step needed two or more SQP iterations or had an active energy limit,
  // linearise first at v* plus its correction v - v* (when v* itself violates a constraint);
  // the same acceptance test (energy_limited_stepper.cpp).
  bool sqp_predictor = true;
  // Where the two steps before both left a correction, the predictor adds half of their
  // difference to the last one (energy_limited_stepper.cpp).
  bool sqp_extrapolation = true;
  FactorizationReuse reuse;
};

struct EnergyLimitedStepReport {
  bool converged = false;          // SQP met both nonlinear tolerances
  int pgs_unconverged = 0;         // LCP solves that stopped at the PGS iteration cap
  int sqp_iterations = 0;          // LCP solves (0: the unconstrained step already satisfied all)
  int pgs_iterations = 0;          // summed over the SQP iterations
  double pgs_residual = 0.0;       // of the last LCP solve
  double energy_violation = 0.0;   // max_e (U_e / U_max - 1), clamped at 0, at the end of the step
  double penetration = 0.0;        // max contact penetration (m), at the end of the step
  int active_energy = 0;           // energy rows with lambda > 0 in the last LCP
  int active_contacts = 0;         // contact normal rows with lambda > 0 in the last LCP
  double max_element_energy = 0.0;
  int factorizations = 0;          // CHOLMOD numeric factorisations in this step
  int cg_iterations = 0;           // preconditioned CG iterations (lagged factorisation)
  int splitting_iterations = 0;    // LCP splitting sweeps, summed over the SQP iterations
  // Wall-clock split: the whole step; numeric factorisations; the SQP/LCP loop and, inside it,
  // linear solves (CG or direct, outside factorisations), forming W~, and PGS.
  double seconds = 0.0, factor_seconds = 0.0, lcp_seconds = 0.0;
  double solve_seconds = 0.0, w_seconds = 0.0, pgs_seconds = 0.0;
};

// A run's or a frame's step reports summed up (the benchmark, the tests and summary.json).
struct EnergyLimitedStepTotals {
  int steps = 0, sqp_iterations = 0, pgs_iterations = 0, unconverged_steps = 0;
  int max_sqp_iterations = 0, max_active_energy = 0, max_active_contacts = 0;
  int factorizations = 0, cg_iterations = 0, splitting_iterations = 0;
  // Steps that ended with an active constraint, and the active rows summed over them (energy
  // rows and contact normals with lambda > 0), for the paper's "average number of constraints".
  int active_steps = 0;
  long active_rows = 0, active_energy_rows = 0;
  double active_seconds = 0.0;
  double mean_active_rows() const { return active_steps ? double(active_rows) / active_steps : 0.0; }
  double mean_active_energy_rows() const { return active_steps ? double(active_energy_rows) / active_steps : 0.0; }
  double ms_per_active_step() const { return active_steps ? 1e3 * active_seconds / active_steps : 0.0; }
  double factor_seconds = 0.0, lcp_seconds = 0.0, solve_seconds = 0.0, w_seconds = 0.0, pgs_seconds = 0.0;
  double seconds = 0.0, max_energy_violation = 0.0, max_element_energy = 0.0;
  double max_pgs_residual = 0.0, max_penetration = 0.0;
  double ms_per_step() const { return steps ? 1e3 * seconds / steps : 0.0; }
  void add(const EnergyLimitedStepReport& r);
};

class EnergyLimitedStepper {
 public:
  // `potential`: the potential energy as a sum of forms (elastic, loads, bone springs, ...) over
  // all DOFs, without Dirichlet DOFs of its own (the stepper prescribes velocities instead);
  // `limited`: the element form whose element energies the energy limit bounds (one of
  // potential's forms); `masses`: lumped nodal masses per vertex; `contacts` may be empty.
  EnergyLimitedStepper(std::shared_ptr<Problem> potential, std::shared_ptr<const ElementForm> limited,
                       Eigen::VectorXd masses, ContactProvider contacts, EnergyLimitedStepSettings settings);
  // An elastic element form and constant external forces (3V); `fixed`: per DOF, 1 where the
  // velocity is held at zero.
  EnergyLimitedStepper(std::shared_ptr<ElementForm> elastic, Eigen::VectorXd masses, Eigen::VectorXd external,
                       std::vector<char> fixed, ContactProvider contacts, EnergyLimitedStepSettings settings);
  ~EnergyLimitedStepper();

  // Advances (x, v) by one time step, from time() to time() + time_step, with the DOFs of the
  // constructor's `fixed` mask held at zero velocity.
  EnergyLimitedStepReport step(Eigen::VectorXd& x, Eigen::VectorXd& v);
  // The same with prescribed motion: DOFs flagged in `fixed` reach x_end at the step's end
  // (velocity (x_end - x) / h over the step); the others are free.
  EnergyLimitedStepReport step(Eigen::VectorXd& x, Eigen::VectorXd& v, const std::vector<char>& fixed,
                               const Eigen::VectorXd& x_end);

  // Simulated time (s) at the start of the next step; moving obstacles are evaluated from it.
  double time() const { return time_; }
  void set_time(double seconds) { time_ = seconds; }

  // Multipliers of the last step's final LCP by constraint key: the next step's warm start and
  // first Lagrangian Hessian. A resumed run restores them with the positions and velocities.
  const std::map<long, double>& multipliers() const { return multipliers_; }
  void set_multipliers(std::map<long, double> multipliers) { multipliers_ = std::move(multipliers); }
  // The SQP predictor of the next step (the last step's v - v*, extrapolated from the one
  // before where that step left one too; or empty) and the last step's v - v* itself (or empty):
  // a resumed run restores both with the multipliers, so that it takes the steps an
  // uninterrupted one takes.
  const Eigen::VectorXd& predictor() const { return predictor_; }
  void set_predictor(Eigen::VectorXd predictor) { predictor_ = std::move(predictor); }
  const Eigen::VectorXd& correction() const { return correction_; }
  void set_correction(Eigen::VectorXd correction) { correction_ = std::move(correction); }

  const EnergyLimitedStepSettings& settings() const { return settings_; }
  const ElementForm& limited_form() const { return *limited_; }

 private:
  struct Factorization;
  std::shared_ptr<Problem> potential_;
  std::shared_ptr<const ElementForm> limited_;
  Eigen::VectorXd mass_dofs_;
  std::vector<char> fixed_;  // the default mask of step(x, v)
  ContactProvider contacts_;
  EnergyLimitedStepSettings settings_;
  std::unique_ptr<Factorization> factor_;
  std::map<long, double> multipliers_;  // of the last step's final LCP, by constraint key
  Eigen::VectorXd predictor_;           // the next step's guess of v - v* (empty: no prediction)
  Eigen::VectorXd correction_;          // the last step's v - v* (empty: it left none)
  double time_ = 0.0;
};

}  // namespace sinew
