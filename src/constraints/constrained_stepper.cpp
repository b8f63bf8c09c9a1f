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
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;         // A
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> lagrangian;  // H of the SQP model
  bool analysed = false, lagrangian_analysed = false;
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

ConstrainedStepReport ConstrainedStepper::step(Eigen::VectorXd& x, Eigen::VectorXd& v) {
  const auto t_step = Clock::now();
  ConstrainedStepReport report;
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

  // ---- SQP: linearise at x_k = x0 + h v_k and solve the subproblem
  //   min 1/2 (v - v*)^T A (v - v*)  s.t.  C(x_k) / h + J_k (v - v_k) >= 0 (+ friction),
  // whose Newton step from v_k is v_k - H^-1 g + H^-1 J^T lambda with g = A (v_k - v*).
  const std::optional<EnergyLimit>& limit = settings_.energy_limit;
  Eigen::VectorXd v_k = v_star;
  std::map<long, double> warm;  // multipliers of the previous LCP by constraint key
  std::map<long, char> ever_active;
  auto t_lcp = Clock::now();
  for (int k = 0;; ++k) {
    const Eigen::VectorXd x_k = x0 + h * v_k;
    // Nonlinear violation at x_k; gather the rows to linearise. Row offsets: c / h for
    // unilateral rows, the current sliding velocity J v_k - t . v_obstacle for friction rows.
    std::vector<Row> rows;
    double energy_violation = 0.0, max_energy = 0.0;
    for (Eigen::Index e = 0; e < disc.num_elements(); ++e) {
      const double U = model_->element_energy(e, x_k);
      max_energy = std::max(max_energy, U);
      if (!limit) continue;
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
      r.offset = (1.0 - U / limit->max_energy) / h;  // C(x_k) / h (Eq. 22)
      rows.push_back(std::move(r));
    }
    double penetration = 0.0;
    const std::vector<ContactCandidate> candidates = contacts_ ? contacts_(x_k, time_, time_ + h) : std::vector<ContactCandidate>{};
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
      normal.offset = c.gap / h;
      const int normal_index = static_cast<int>(rows.size());
      rows.push_back(std::move(normal));
      if (c.friction > 0.0) {
        const auto [t1, t2] = tangents(c.normal);
        int s = 1;
        for (const Vec3& tangent : {t1, t2}) {
          Row r = make_row(tangent);
          r.key = -1 - 3L * c.vertex - s++;
          r.bounds = {normal_index, c.friction};
          r.offset = row_dot(r, v_k) - tangent.dot(c.obstacle_velocity);  // target: no sliding
          rows.push_back(std::move(r));
        }
      }
    }
    report.energy_violation = std::max(0.0, energy_violation);
    report.penetration = penetration;
    report.max_element_energy = max_energy;
    const bool satisfied = energy_violation <= settings_.energy_tolerance && penetration <= settings_.contact_tolerance;
    if (satisfied || k >= settings_.sqp_max_iterations) {
      report.converged = satisfied;
      v = v_k;
      break;
    }

    // ---- quadratic model: H = A plus the curvature of the energy constraints with lambda > 0
    auto* solver = &factor_->llt;
    if (limit && k > 0) {
      std::vector<Eigen::Triplet<double>> extra;
      for (const auto& [key, lambda_e] : warm) {
        if (key < 0 || lambda_e <= 0.0) continue;  // contact rows are linear
        const Eigen::MatrixXd He = model_->element_energy_hessian(key, x_k) * (h * lambda_e / limit->max_energy);
        for (int a = 0; a < disc.nodes(); ++a)
          for (int o = 0; o < disc.nodes(); ++o)
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 3; ++j) {
                const Eigen::Index r = 3 * elements(key, a) + i, c = 3 * elements(key, o) + j;
                if (!fixed_[r] && !fixed_[c]) extra.emplace_back(r, c, He(3 * a + i, 3 * o + j));
              }
      }
      if (!extra.empty()) {
        Eigen::SparseMatrix<double> E(n, n);
        E.setFromTriplets(extra.begin(), extra.end());
        const Eigen::SparseMatrix<double> H = A + E;  // same pattern: A holds every element block
        if (!factor_->lagrangian_analysed) factor_->lagrangian.analyzePattern(H);
        factor_->lagrangian_analysed = true;
        factor_->lagrangian.factorize(H);
        if (factor_->lagrangian.info() != Eigen::Success) {
          factor_->lagrangian.analyzePattern(H);
          factor_->lagrangian.factorize(H);
        }
        if (factor_->lagrangian.info() != Eigen::Success)
          throw Error("SQP Lagrangian Hessian is not positive definite", "constrained stepper");
        solver = &factor_->lagrangian;
      }
    }
    const Eigen::VectorXd d0 = k == 0 ? Eigen::VectorXd::Zero(n) : Eigen::VectorXd(solver->solve(A * (v_k - v_star)));

    // ---- LCP (Eq. 23): W = J H^-1 J^T with the columns H^-1 J^T from the one factorisation
    const Eigen::Index m = static_cast<Eigen::Index>(rows.size());
    Eigen::VectorXd q(m), lambda(m);
    std::vector<LcpRow> bounds(m);
    std::vector<Eigen::Triplet<double>> entries;
    for (Eigen::Index i = 0; i < m; ++i) {
      for (const auto& [dof, value] : rows[i].jacobian) entries.emplace_back(i, dof, value);
      q(i) = rows[i].offset - row_dot(rows[i], d0);
      bounds[i] = rows[i].bounds;
      const auto w = warm.find(rows[i].key);
      lambda(i) = w == warm.end() ? 0.0 : w->second;
    }
    Eigen::SparseMatrix<double, Eigen::RowMajor> J(m, n);
    J.setFromTriplets(entries.begin(), entries.end());
    const Eigen::MatrixXd Jt = Eigen::MatrixXd(J.transpose());
    const Eigen::MatrixXd Y = solver->solve(Jt);  // H^-1 J^T: one multi-RHS solve
    // W = J Y as a sparse-times-dense product: each row of J has at most 24 entries, so this is
    // O(nnz(J) m) with contiguous access to Y's rows' columns, not m^2 scattered row dots.
    Eigen::MatrixXd W = J * Y;
    for (Eigen::Index i = 0; i < m; ++i) W(i, i) = std::max(W(i, i), 1e-14 * W.diagonal().cwiseAbs().maxCoeff());
    const PgsReport pgs = solve_pgs(W, q, bounds, lambda, settings_.pgs);
    report.sqp_iterations = k + 1;
    report.pgs_iterations += pgs.iterations;
    report.pgs_residual = pgs.residual;
    report.pgs_unconverged += pgs.converged ? 0 : 1;
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
    v_k = v_k - d0 + Y * lambda;  // Eq. 21 for k = 0
  }
  report.lcp_seconds = since(t_lcp);
  x = x0 + h * v;
  time_ += h;
  report.seconds = since(t_step);
  return report;
}

}  // namespace sinew
