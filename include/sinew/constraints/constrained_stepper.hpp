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
#include <memory>
#include <optional>
#include <vector>

#include "sinew/constraints/contact.hpp"
#include "sinew/constraints/energy_limit.hpp"
#include "sinew/constraints/pgs.hpp"

namespace sinew {

struct ConstrainedStepSettings {
  double time_step = 0.01;
  std::optional<EnergyLimit> energy_limit;
  // Elements with U_e >= (1 - activation) U_max enter the LCP (the others cannot reach the
  // limit within one linearisation and would only cost PGS work).
  double activation = 0.1;
  PgsSettings pgs;
  int sqp_max_iterations = 20;
  double energy_tolerance = 1e-3;   // accept U_e <= (1 + tol) U_max
  double contact_tolerance = 1e-4;  // accept penetration up to this depth (m)
};

struct ConstrainedStepReport {
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
  double seconds = 0.0, factor_seconds = 0.0, lcp_seconds = 0.0;
};

class ConstrainedStepper {
 public:
  // `masses`: lumped nodal masses per vertex; `external`: constant external forces (3V);
  // `fixed`: per DOF, 1 where the velocity is held at zero; `contacts` may be empty.
  ConstrainedStepper(std::shared_ptr<const ElementEnergyModel> model, Eigen::VectorXd masses,
                     Eigen::VectorXd external, std::vector<char> fixed, ContactProvider contacts,
                     ConstrainedStepSettings settings);
  ~ConstrainedStepper();

  // Advances (x, v) by one time step, from time() to time() + time_step.
  ConstrainedStepReport step(Eigen::VectorXd& x, Eigen::VectorXd& v);

  // Simulated time (s) at the start of the next step; moving obstacles are evaluated from it.
  double time() const { return time_; }
  void set_time(double seconds) { time_ = seconds; }

  const ConstrainedStepSettings& settings() const { return settings_; }
  const ElementEnergyModel& model() const { return *model_; }

 private:
  struct Factorization;
  std::shared_ptr<const ElementEnergyModel> model_;
  Eigen::VectorXd mass_dofs_, external_;
  std::vector<char> fixed_;
  ContactProvider contacts_;
  ConstrainedStepSettings settings_;
  std::unique_ptr<Factorization> factor_;
  double time_ = 0.0;
};

}  // namespace sinew
