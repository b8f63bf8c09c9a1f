#include "sinew/constraints/constrained_stepper.hpp"

#include <Eigen/CholmodSupport>
#include <chrono>
#include <map>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// One linearised constraint: a sparse row of J over DOFs, its LCP offset and bounds.
struct Row {
  std::vector<std::pair<Eigen::Index, double>> jacobian;  // (dof, value)
  double offset = 0.0;  // q_i
  LcpRow bounds;
  long key = 0;         // identifies the constraint across SQP iterations (warm start)
  bool energy = false;
};

double row_dot(const Row& r, const Eigen::VectorXd& v) {
  double s = 0.0;
  for (const auto& [dof, value] : r.jacobian) s += value * v(dof);
  return s;
}

// Two unit tangents orthogonal to n.
std::pair<Vec3, Vec3> tangents(const Vec3& n) {
  const Vec3 a = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 t1 = n.cross(a).normalized();
  return {t1, n.cross(t1)};
}

}  // namespace

struct ConstrainedStepper::Factorization {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  bool analysed = false;
};

ConstrainedStepper::ConstrainedStepper(std::shared_ptr<const ElementEnergyModel> model, Eigen::VectorXd masses,
                                       Eigen::VectorXd external, std::vector<char> fixed, ContactProvider contacts,
                                       ConstrainedStepSettings settings)
    : model_(std::move(model)),
      external_(std::move(external)),
      fixed_(std::move(fixed)),
      contacts_(std::move(contacts)),
      settings_(settings),
      factor_(std::make_unique<Factorization>()) {
  const Eigen::Index n = model_->discretization().num_dofs();
  if (masses.size() * 3 != n || external_.size() != n || static_cast<Eigen::Index>(fixed_.size()) != n)
    throw Error("masses, forces and fixed DOFs do not match the mesh", "constrained stepper");
  if (!(settings_.time_step > 0.0)) throw Error("time step must be positive", "constrained stepper");
  if (settings_.energy_limit && !model_->supports(settings_.energy_limit->jacobian))
    throw Error(std::string("the ") + model_->name() + " model has no " + to_string(settings_.energy_limit->jacobian) +
                    " Jacobian",
                "constrained stepper");
  mass_dofs_.resize(n);
  for (Eigen::Index v = 0; v < masses.size(); ++v) mass_dofs_.segment<3>(3 * v).setConstant(masses(v));
}

ConstrainedStepper::~ConstrainedStepper() = default;

StepReport ConstrainedStepper::step(Eigen::VectorXd& x, Eigen::VectorXd& v) {
  const auto t_step = Clock::now();
  StepReport report;
  const double h = settings_.time_step;
  const Discretization& disc = model_->discretization();
  const auto& elements = disc.mesh().elements;
  const Eigen::Index n = x.size();
  const Eigen::VectorXd x0 = x;

  // ---- unconstrained backward Euler (Eq. 19): (M + h^2 K) v* = M v0 + h f(x0)
  auto t = Clock::now();
  Eigen::SparseMatrix<double> A = h * h * model_->stiffness(x0);
  Eigen::VectorXd b = mass_dofs_.cwiseProduct(v) + h * (model_->forces(x0) + external_);
  for (Eigen::Index k = 0; k < A.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it)
      if (fixed_[it.row()] || fixed_[it.col()]) it.valueRef() = 0.0;
  Eigen::SparseMatrix<double> Mdiag(n, n);
  {
    std::vector<Eigen::Triplet<double>> d;
    for (Eigen::Index i = 0; i < n; ++i) d.emplace_back(i, i, fixed_[i] ? 1.0 : mass_dofs_(i));
    Mdiag.setFromTriplets(d.begin(), d.end());
  }
  A += Mdiag;
  for (Eigen::Index i = 0; i < n; ++i)
    if (fixed_[i]) b(i) = 0.0;
  if (!factor_->analysed) {
    factor_->llt.analyzePattern(A);
    factor_->analysed = true;
  }
  factor_->llt.factorize(A);
  if (factor_->llt.info() != Eigen::Success) {
    factor_->llt.analyzePattern(A);  // the pattern can change when the warped stiffness cancels entries
    factor_->llt.factorize(A);
    if (factor_->llt.info() != Eigen::Success) throw Error("backward-Euler matrix is not positive definite", "constrained stepper");
  }
  const Eigen::VectorXd v_star = factor_->llt.solve(b);
  report.factor_seconds = since(t);

  // ---- SQP: linearise at x_k = x0 + h v_k, solve the LCP, repeat while violated
  const std::optional<EnergyLimit>& limit = settings_.energy_limit;
  Eigen::VectorXd v_k = v_star;
  std::map<long, double> warm;  // multipliers of the previous LCP by constraint key
  std::map<long, char> ever_active;
  auto t_lcp = Clock::now();
  for (int k = 0;; ++k) {
    const Eigen::VectorXd x_k = x0 + h * v_k;
    // Nonlinear violation at x_k; gather the rows to linearise.
    std::vector<Row> rows;
    double energy_violation = 0.0, max_energy = 0.0;
    if (limit) {
      for (Eigen::Index e = 0; e < disc.num_elements(); ++e) {
        const double U = model_->element_energy(e, x_k);
        max_energy = std::max(max_energy, U);
        energy_violation = std::max(energy_violation, U / limit->max_energy - 1.0);
        if (U < (1.0 - settings_.activation) * limit->max_energy && !ever_active.count(e)) continue;
        const Eigen::VectorXd jac = energy_constraint_jacobian(*model_, e, x_k, *limit);
        Row r;
        r.energy = true;
        r.key = e;
        for (int a = 0; a < disc.nodes(); ++a)
          for (int i = 0; i < 3; ++i) {
            const Eigen::Index dof = 3 * elements(e, a) + i;
            if (!fixed_[dof]) r.jacobian.emplace_back(dof, jac(3 * a + i));
          }
        if (r.jacobian.empty()) continue;  // a fully fixed element cannot be helped
        // C(x_k) + h J (v - v_k) >= 0 with v = v* + A^-1 J^T lambda (Eq. 22, 23).
        r.offset = (1.0 - U / limit->max_energy) / h + row_dot(r, v_star) - row_dot(r, v_k);
        rows.push_back(std::move(r));
      }
    } else {
      for (Eigen::Index e = 0; e < disc.num_elements(); ++e) max_energy = std::max(max_energy, model_->element_energy(e, x_k));
    }
    double penetration = 0.0;
    const std::vector<ContactCandidate> candidates = contacts_ ? contacts_(x_k) : std::vector<ContactCandidate>{};
    for (const ContactCandidate& c : candidates) {
      penetration = std::max(penetration, -c.gap);
      const Eigen::Index base = 3 * static_cast<Eigen::Index>(c.vertex);
      if (fixed_[base] && fixed_[base + 1] && fixed_[base + 2]) continue;
      auto make_row = [&](const Vec3& dir) {
        Row r;
        for (int i = 0; i < 3; ++i)
          if (!fixed_[base + i] && dir(i) != 0.0) r.jacobian.emplace_back(base + i, dir(i));
        return r;
      };
      Row normal = make_row(c.normal);
      normal.key = -1 - 3L * c.vertex;
      normal.offset = c.gap / h + row_dot(normal, v_star) - row_dot(normal, v_k);
      const int normal_index = static_cast<int>(rows.size());
      rows.push_back(std::move(normal));
      if (c.friction > 0.0) {
        const auto [t1, t2] = tangents(c.normal);
        int s = 1;
        for (const Vec3& tangent : {t1, t2}) {
          Row r = make_row(tangent);
          r.key = -1 - 3L * c.vertex - s++;
          r.bounds = {normal_index, c.friction};
          // Sticking target: zero sliding velocity relative to the obstacle.
          r.offset = row_dot(r, v_star) - tangent.dot(c.obstacle_velocity);
          rows.push_back(std::move(r));
        }
      }
    }
    report.energy_violation = energy_violation;
    report.penetration = penetration;
    report.max_element_energy = max_energy;
    const bool satisfied = energy_violation <= settings_.energy_tolerance && penetration <= settings_.contact_tolerance;
    // Stop when the nonlinear constraints hold (after at least one LCP if any was violated, so
    // friction of resting contacts is applied), or when the iteration budget is spent.
    if (satisfied || k >= settings_.sqp_max_iterations) {
      report.converged = satisfied && (k == 0 || report.pgs_residual <= settings_.pgs.tolerance);
      v = v_k;
      break;
    }

    // ---- LCP (Eq. 23): W = J A^-1 J^T with the columns A^-1 J^T from the one factorisation
    const Eigen::Index m = static_cast<Eigen::Index>(rows.size());
    Eigen::MatrixXd Jt = Eigen::MatrixXd::Zero(n, m);
    Eigen::VectorXd q(m), lambda(m);
    std::vector<LcpRow> bounds(m);
    for (Eigen::Index i = 0; i < m; ++i) {
      for (const auto& [dof, value] : rows[i].jacobian) Jt(dof, i) += value;
      q(i) = rows[i].offset;
      bounds[i] = rows[i].bounds;
      const auto w = warm.find(rows[i].key);
      lambda(i) = w == warm.end() ? 0.0 : w->second;
    }
    const Eigen::MatrixXd Y = factor_->llt.solve(Jt);  // A^-1 J^T
    Eigen::MatrixXd W(m, m);
    for (Eigen::Index i = 0; i < m; ++i)
      for (Eigen::Index j = 0; j < m; ++j) W(i, j) = row_dot(rows[i], Y.col(j));
    for (Eigen::Index i = 0; i < m; ++i) W(i, i) = std::max(W(i, i), 1e-14 * W.diagonal().cwiseAbs().maxCoeff());
    const PgsReport pgs = solve_pgs(W, q, bounds, lambda, settings_.pgs);
    report.sqp_iterations = k + 1;
    report.pgs_iterations += pgs.iterations;
    report.pgs_residual = pgs.residual;
    report.active_energy = report.active_contacts = 0;
    warm.clear();
    for (Eigen::Index i = 0; i < m; ++i) {
      warm[rows[i].key] = lambda(i);
      if (rows[i].bounds.normal >= 0 || lambda(i) <= 0.0) continue;
      if (rows[i].energy) {
        ++report.active_energy;
        ever_active[rows[i].key] = 1;
      } else {
        ++report.active_contacts;
      }
    }
    v_k = v_star + Y * lambda;  // Eq. 21
  }
  report.lcp_seconds = since(t_lcp);
  x = x0 + h * v;
  report.seconds = since(t_step);
  return report;
}

}  // namespace sinew
