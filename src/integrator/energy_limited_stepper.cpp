#include "sinew/integrator/energy_limited_stepper.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>

#include "sinew/core/error.hpp"
#include "sinew/forms/external_force_form.hpp"
#include "sinew/solver/lagged_factorization.hpp"
#include "sinew/solver/serial_openmp.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace sinew {
namespace {

// Below this many elements a step runs on one thread: an element's share of any loop costs
// about a microsecond, less than waking a worker, and paper 001's 27- and 56-hexahedron scenes
// spent several percent of their time in oneTBB's dispatch and the workers' wake-ups.
constexpr Eigen::Index kOneThreadBelow = 128;

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

// The matrix whose row i is rows(i) (a sparse row as (dof, value) pairs), filled in order with
// each row's entries sorted by DOF and repeated DOFs summed in the order given, as
// setFromTriplets would, but without its triplet list and transposed copy.
template <class RowOf>
void set_rows(Eigen::SparseMatrix<double, Eigen::RowMajor>& J, Eigen::Index m, Eigen::Index n, const RowOf& rows) {
  Eigen::Index nnz = 0;
  for (Eigen::Index i = 0; i < m; ++i) nnz += static_cast<Eigen::Index>(rows(i).size());
  J.resize(m, n);
  J.reserve(nnz);
  std::vector<std::pair<Eigen::Index, double>> sorted;
  for (Eigen::Index i = 0; i < m; ++i) {
    J.startVec(i);
    const auto& row = rows(i);
    sorted.assign(row.begin(), row.end());
    std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t k = 0; k < sorted.size();) {
      const Eigen::Index dof = sorted[k].first;
      double value = sorted[k].second;
      for (++k; k < sorted.size() && sorted[k].first == dof; ++k) value += sorted[k].second;
      J.insertBack(i, dof) = value;
    }
  }
  J.finalize();
}

// Two unit tangents orthogonal to n.
std::pair<Vec3, Vec3> tangents(const Vec3& n) {
  const Vec3 a = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 t1 = n.cross(a).normalized();
  return {t1, n.cross(t1)};
}

// The constraints linearised at x_k (Eq. 22) and the nonlinear violations there: an energy row
// for every element within `activation` of the limit or active earlier in the step, and a
// normal row plus two friction rows per contact candidate. Row offsets: C / h for unilateral
// rows, the current sliding velocity J v_k - t . v_obstacle for friction rows.
struct Linearisation {
  std::vector<Row> rows;
  double energy_violation = 0.0, max_energy = 0.0, penetration = 0.0;
  bool satisfied = false;  // both nonlinear tolerances hold at x_k (then `rows` is empty)
};

Linearisation linearise_constraints(const ElementForm& model, const EnergyLimitedStepSettings& settings,
                                    const std::vector<char>& fixed, const ContactProvider& contacts, double time,
                                    const Eigen::VectorXd& x_k, const Eigen::VectorXd& v_k,
                                    const std::map<long, char>& ever_active, bool final_iteration,
                                    bool rows_even_if_satisfied = false) {
  const double h = settings.time_step;
  const Discretization& disc = model.discretization();
  const auto& elements = disc.mesh().elements;
  const std::optional<EnergyLimit>& limit = settings.energy_limit;
  Linearisation lin;
  std::vector<Row>& rows = lin.rows;
  // Element energies, and the Jacobians of the elements that get a row, in parallel. The grains
  // keep small meshes (paper 001's 27 and 56 hexahedra) on one thread: an element costs about a
  // microsecond, less than waking a worker.
  std::vector<double> energies;
  model.element_values(x_k, energies);
  std::vector<Eigen::Index> limited;
  for (Eigen::Index e = 0; e < disc.num_elements(); ++e) {
    const double U = energies[static_cast<size_t>(e)];
    lin.max_energy = std::max(lin.max_energy, U);
    if (!limit) continue;
    lin.energy_violation = std::max(lin.energy_violation, U / limit->max_energy - 1.0);
    if (U >= (1.0 - settings.activation) * limit->max_energy || ever_active.count(e)) limited.push_back(e);
  }
  // The candidates first: when the constraints already hold (or the SQP is out of iterations)
  // the step ends here, and the Jacobians would go unused.
  const std::vector<ContactCandidate> candidates = contacts ? contacts(x_k, time, time + h) : std::vector<ContactCandidate>{};
  for (const ContactCandidate& c : candidates) lin.penetration = std::max(lin.penetration, -c.gap);
  lin.satisfied = lin.energy_violation <= settings.energy_tolerance && lin.penetration <= settings.contact_tolerance;
  if ((lin.satisfied && !rows_even_if_satisfied) || final_iteration) return lin;
  std::vector<Eigen::VectorXd> jacobians(limited.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, limited.size(), 32), [&](const auto& range) {
    for (size_t i = range.begin(); i < range.end(); ++i) jacobians[i] = energy_constraint_jacobian(model, limited[i], x_k, *limit);
  });
  for (size_t l = 0; l < limited.size(); ++l) {
    const Eigen::Index e = limited[l];
    const double U = energies[static_cast<size_t>(e)];
    const Eigen::VectorXd& jac = jacobians[l];
    Row r;
    r.energy = true;
    r.key = e;
    for (int a = 0; a < disc.nodes(); ++a)
      for (int i = 0; i < 3; ++i) {
        const Eigen::Index dof = 3 * elements(e, a) + i;
        if (!fixed[dof]) r.jacobian.emplace_back(dof, jac(3 * a + i));
      }
    if (r.jacobian.empty()) continue;  // a fully fixed element cannot be helped
    r.offset = (1.0 - U / limit->max_energy) / h;  // C(x_k) / h (Eq. 22)
    rows.push_back(std::move(r));
  }
  for (const ContactCandidate& c : candidates) {
    const Eigen::Index base = 3 * static_cast<Eigen::Index>(c.vertex);
    if (fixed[base] && fixed[base + 1] && fixed[base + 2]) continue;
    auto make_row = [&](const Vec3& dir) {
      Row r;
      for (int i = 0; i < 3; ++i)
        if (!fixed[base + i] && dir(i) != 0.0) r.jacobian.emplace_back(base + i, dir(i));
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
  return lin;
}

// Whether an element with an active energy row in `multipliers` (lambda > 0) exceeds the limit
// beyond the tolerance at x: the same test, element by element, as linearise_constraints makes
// over the whole mesh (the rotations come from the same cache state, so the energies are the
// same bit for bit). A predicted step's v* mostly fails on these elements, and then the test
// ends without a whole-mesh pass of rotations and energies.
bool active_limit_violated(const ElementForm& model, const EnergyLimitedStepSettings& settings,
                           const std::map<long, double>& multipliers, const Eigen::VectorXd& x) {
  if (!settings.energy_limit) return false;
  const double max_energy = settings.energy_limit->max_energy;
  for (const auto& [key, lambda] : multipliers) {
    if (key < 0 || lambda <= 0.0) continue;  // contact rows
    if (model.element_value(key, x) / max_energy - 1.0 > settings.energy_tolerance) return true;
  }
  return false;
}

}  // namespace

// Two lagged factorisations: one of a backward-Euler matrix A (first SQP iteration) and one of
// a Lagrangian Hessian H (later iterations; A with the limit-active elements stiffened). Each
// preconditions the matrices of its kind, which change slowly from step to step, while A and H
// differ much more from each other.
//
// The step's matrices live here too, so that their storage is reused from step to step (on
// small meshes allocating and freeing them cost as much as the arithmetic), with, per element,
// the positions of its 24 x 24 block among A's stored values, so that H = A + element blocks is
// a copy and indexed additions.
struct EnergyLimitedStepper::Factorization {
  // Steps of meshes below kOneThreadBelow elements run here, on the calling thread alone.
  tbb::task_arena one_thread{1};
  LaggedFactorization backward_euler, lagrangian;
  Eigen::SparseMatrix<double> A, H;
  Eigen::MatrixXd element_hessian;  // an active element's Hessian block, storage reused
  // Per element (filled when it is first stiffened): the index among A's values of each entry of
  // its block, row-major over the element's DOFs; valid for the pattern below.
  std::vector<std::vector<int>> block_slots;
  std::vector<int> slots_outer, slots_inner;  // A's pattern the slots were found for

  // A = scale K for the potential's Hessian K. When K's pattern is the one the slots were found
  // for (the usual case: it is built once), only the values are written, scaled in the same
  // pass; otherwise A takes K's pattern and the slots are dropped. `k_pattern` is K's pattern id
  // (LinearOperator::pattern_id): the one seen last stands for the pattern; 0 (unknown) or a new
  // id compares the patterns.
  void set_scaled(const Eigen::SparseMatrix<double>& K, double scale, std::uint64_t k_pattern) {
    const bool sizes = K.isCompressed() && static_cast<Eigen::Index>(slots_outer.size()) == K.outerSize() + 1 &&
                       static_cast<Eigen::Index>(slots_inner.size()) == K.nonZeros() &&
                       A.outerSize() == K.outerSize() && A.nonZeros() == K.nonZeros() && A.isCompressed();
    const bool same = sizes && ((k_pattern != 0 && k_pattern == last_k_pattern) ||
                                (std::equal(slots_outer.begin(), slots_outer.end(), K.outerIndexPtr()) &&
                                 std::equal(slots_inner.begin(), slots_inner.end(), K.innerIndexPtr())));
    last_k_pattern = k_pattern;
    if (same) {
      Eigen::Map<Eigen::VectorXd>(A.valuePtr(), A.nonZeros()) =
          Eigen::Map<const Eigen::VectorXd>(K.valuePtr(), K.nonZeros()) * scale;
      return;
    }
    A = K;
    A.makeCompressed();
    A *= scale;
    slots_outer.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
    slots_inner.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
    triple_columns.assign(static_cast<size_t>(A.outerSize()), 0);
    for (Eigen::Index c = 0; c + 2 < A.outerSize(); c += 3) {
      const int* outer = A.outerIndexPtr();
      const int* inner = A.innerIndexPtr();
      const int length = outer[c + 1] - outer[c];
      triple_columns[static_cast<size_t>(c)] =
          outer[c + 2] - outer[c + 1] == length && outer[c + 3] - outer[c + 2] == length &&
          std::equal(inner + outer[c], inner + outer[c + 1], inner + outer[c + 1]) &&
          std::equal(inner + outer[c], inner + outer[c + 1], inner + outer[c + 2]);
    }
    block_slots.clear();
    scatter_valid = false;
    h_pattern_current = false;
    ++pattern;
  }
  // H = A with A's values, in H's storage when it already has A's pattern.
  void copy_a_into_h() {
    if (h_pattern_current) {
      std::copy(A.valuePtr(), A.valuePtr() + A.nonZeros(), H.valuePtr());
      return;
    }
    H = A;
    h_pattern_current = true;
  }
  bool h_pattern_current = false;  // H has A's pattern (set_scaled clears it when that changes)
  // Per column of A: 1 where it starts a vertex's three columns with the same rows.
  std::vector<char> triple_columns;
  // y = A x, the same sums as Eigen's A * x (column by column, each added to y's rows in column
  // order), with a vertex's three columns in one pass over their common rows: y's entries are
  // read and written once per vertex instead of once per column.
  void multiply_a(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
    const int* outer = A.outerIndexPtr();
    const int* inner = A.innerIndexPtr();
    const double* values = A.valuePtr();
    y.setZero(A.rows());
    double* ys = y.data();
    for (Eigen::Index c = 0; c < A.outerSize();) {
      if (triple_columns[static_cast<size_t>(c)]) {
        const double x0 = x(c), x1 = x(c + 1), x2 = x(c + 2);
        const int begin = outer[c], length = outer[c + 1] - begin;
        const double* v0 = values + begin;
        const double* v1 = values + outer[c + 1];
        const double* v2 = values + outer[c + 2];
        const int* rows = inner + begin;
        for (int k = 0; k < length; ++k) {
          double& yr = ys[rows[k]];
          yr = ((yr + v0[k] * x0) + v1[k] * x1) + v2[k] * x2;
        }
        c += 3;
        continue;
      }
      const double xc = x(c);
      for (int k = outer[c]; k < outer[c + 1]; ++k) ys[inner[k]] += values[k] * xc;
      ++c;
    }
  }
  std::uint64_t last_k_pattern = 0;  // the potential Hessian's pattern id set_scaled saw last
  // The id of A's pattern (and H's, which is A's) for the factorisations, so that they need not
  // compare the patterns of every matrix they are given; set_scaled changes it with the pattern.
  std::uint64_t pattern = 0;
  // Where A = h^2 K becomes M + h^2 K with the fixed DOFs' rows and columns replaced by identity
  // ones: the value positions to clear and, per DOF, its diagonal's position and what is added
  // there (its mass, or 1 on a fixed DOF). Valid for the pattern above and the fixed mask.
  struct Scatter {
    std::vector<int> cleared, diagonal;
    std::vector<double> diagonal_add;
  };
  Scatter scatter_map;
  std::vector<char> scatter_fixed;
  bool scatter_valid = false;
  const Scatter& scatter(const std::vector<char>& fixed, const Eigen::VectorXd& masses) {
    if (scatter_valid && scatter_fixed == fixed) return scatter_map;
    Scatter& s = scatter_map;
    s.cleared.clear();
    s.diagonal.assign(static_cast<size_t>(A.outerSize()), -1);
    s.diagonal_add.resize(static_cast<size_t>(A.outerSize()));
    for (Eigen::Index c = 0; c < A.outerSize(); ++c)
      for (int k = A.outerIndexPtr()[c]; k < A.outerIndexPtr()[c + 1]; ++k) {
        const Eigen::Index r = A.innerIndexPtr()[k];
        if (fixed[static_cast<size_t>(r)] || fixed[static_cast<size_t>(c)]) s.cleared.push_back(k);
        if (r == c) s.diagonal[static_cast<size_t>(c)] = k;
      }
    for (Eigen::Index c = 0; c < A.outerSize(); ++c) {
      if (s.diagonal[static_cast<size_t>(c)] < 0) throw Error("a vertex belongs to no element", "constrained stepper");
      s.diagonal_add[static_cast<size_t>(c)] = fixed[static_cast<size_t>(c)] ? 1.0 : masses(c);
    }
    scatter_fixed = fixed;
    scatter_valid = true;
    return s;
  }

  const std::vector<int>& slots(const Discretization& disc, Eigen::Index e) {
    block_slots.resize(static_cast<size_t>(disc.num_elements()));
    std::vector<int>& s = block_slots[static_cast<size_t>(e)];
    if (!s.empty()) return s;
    const auto& elements = disc.mesh().elements;
    const int dofs = 3 * disc.nodes();
    s.resize(static_cast<size_t>(dofs * dofs));
    for (int a = 0; a < disc.nodes(); ++a)
      for (int o = 0; o < disc.nodes(); ++o)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            const int r = 3 * elements(e, a) + i, c = 3 * elements(e, o) + j;
            const int* begin = A.innerIndexPtr() + A.outerIndexPtr()[c];
            const int* end = A.innerIndexPtr() + A.outerIndexPtr()[c + 1];
            const int* it = std::lower_bound(begin, end, r);
            if (it == end || *it != r) throw Error("the step matrix lacks an element block entry", "constrained stepper");
            s[static_cast<size_t>((3 * a + i) * dofs + 3 * o + j)] = static_cast<int>(it - A.innerIndexPtr());
          }
    return s;
  }
};

void EnergyLimitedStepTotals::add(const EnergyLimitedStepReport& r) {
  ++steps;
  sqp_iterations += r.sqp_iterations;
  pgs_iterations += r.pgs_iterations;
  unconverged_steps += r.converged ? 0 : 1;
  max_sqp_iterations = std::max(max_sqp_iterations, r.sqp_iterations);
  max_active_energy = std::max(max_active_energy, r.active_energy);
  max_active_contacts = std::max(max_active_contacts, r.active_contacts);
  seconds += r.seconds;
  factorizations += r.factorizations;
  cg_iterations += r.cg_iterations;
  splitting_iterations += r.splitting_iterations;
  if (r.active_energy + r.active_contacts > 0) {
    ++active_steps;
    active_rows += r.active_energy + r.active_contacts;
    active_energy_rows += r.active_energy;
    active_seconds += r.seconds;
  }
  factor_seconds += r.factor_seconds;
  lcp_seconds += r.lcp_seconds;
  solve_seconds += r.solve_seconds;
  w_seconds += r.w_seconds;
  pgs_seconds += r.pgs_seconds;
  max_energy_violation = std::max(max_energy_violation, r.energy_violation);
  max_element_energy = std::max(max_element_energy, r.max_element_energy);
  max_pgs_residual = std::max(max_pgs_residual, r.pgs_residual);
  max_penetration = std::max(max_penetration, r.penetration);
}

EnergyLimitedStepper::EnergyLimitedStepper(std::shared_ptr<Problem> potential, std::shared_ptr<const ElementForm> limited,
                                           Eigen::VectorXd masses, ContactProvider contacts,
                                           EnergyLimitedStepSettings settings)
    : potential_(std::move(potential)),
      limited_(std::move(limited)),
      contacts_(std::move(contacts)),
      settings_(settings),
      factor_(std::make_unique<Factorization>()) {
  const Eigen::Index n = limited_->discretization().num_dofs();
  if (masses.size() * 3 != n || potential_->num_dofs() != n)
    throw Error("masses and forms do not match the mesh", "energy-limited stepper");
  if (!(settings_.time_step > 0.0)) throw Error("time step must be positive", "energy-limited stepper");
  if (settings_.energy_limit && !limited_->supports(settings_.energy_limit->jacobian))
    throw Error(std::string("the ") + limited_->name() + " model has no " + to_string(settings_.energy_limit->jacobian) +
                    " Jacobian",
                "energy-limited stepper");
  fixed_.assign(static_cast<size_t>(n), 0);
  potential_->set_fixed(fixed_);  // the raw Hessian: the stepper handles prescribed DOFs itself
  mass_dofs_.resize(n);
  for (Eigen::Index v = 0; v < masses.size(); ++v) mass_dofs_.segment<3>(3 * v).setConstant(masses(v));
}

namespace {
std::shared_ptr<Problem> elastic_and_external(const std::shared_ptr<ElementForm>& elastic, const Eigen::VectorXd& external) {
  auto p = std::make_shared<Problem>(elastic->discretization().mesh().num_vertices());
  p->add_form(elastic);
  if (external.size() != p->num_dofs()) throw Error("external forces do not match the mesh", "energy-limited stepper");
  if (external.squaredNorm() > 0.0) p->add_form(std::make_shared<ExternalForceForm>(external));
  return p;
}
}  // namespace

EnergyLimitedStepper::EnergyLimitedStepper(std::shared_ptr<ElementForm> elastic, Eigen::VectorXd masses,
                                           Eigen::VectorXd external, std::vector<char> fixed, ContactProvider contacts,
                                           EnergyLimitedStepSettings settings)
    : EnergyLimitedStepper(elastic_and_external(elastic, external), elastic, std::move(masses), std::move(contacts),
                           settings) {
  if (static_cast<Eigen::Index>(fixed.size()) != potential_->num_dofs())
    throw Error("fixed DOFs do not match the mesh", "energy-limited stepper");
  fixed_ = std::move(fixed);
}

EnergyLimitedStepper::~EnergyLimitedStepper() = default;

EnergyLimitedStepReport EnergyLimitedStepper::step(Eigen::VectorXd& x, Eigen::VectorXd& v) {
  return step(x, v, fixed_, x);
}

EnergyLimitedStepReport EnergyLimitedStepper::step(Eigen::VectorXd& x, Eigen::VectorXd& v, const std::vector<char>& fixed,
                                                   const Eigen::VectorXd& x_end) {
  if (limited_->discretization().num_elements() < kOneThreadBelow && tbb::this_task_arena::max_concurrency() > 1)
    return factor_->one_thread.execute([&] { return step(x, v, fixed, x_end); });
  const auto t_step = Clock::now();
  const SerialOpenMpScope serial_cholmod;
  EnergyLimitedStepReport report;
  const double h = settings_.time_step;
  const Discretization& disc = limited_->discretization();
  const auto& elements = disc.mesh().elements;
  const Eigen::Index n = x.size();
  const Eigen::VectorXd x0 = x;
  if (static_cast<Eigen::Index>(fixed.size()) != n || x_end.size() != n)
    throw Error("fixed DOFs or prescribed positions do not match the mesh", "energy-limited stepper");
  // Prescribed velocities of the fixed DOFs over the step (zero for a pinned DOF).
  Eigen::VectorXd v_fixed = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i)
    if (fixed[i]) v_fixed(i) = (x_end(i) - x0(i)) / h;
  potential_->begin_solve(x0);  // forms with lagged state (self-contact targets) take this step's

  // ---- unconstrained backward Euler (Eq. 19): (M + h^2 K) v* = M v0 + h f(x0)
  // The potential's raw Hessian K and forces f = -grad E at x0; the prescribed velocities are
  // lifted to the right-hand side (b -= A v_fixed) before their rows and columns become identity.
  Eigen::SparseMatrix<double>& A = factor_->A;
  const LinearOperator& K = potential_->hessian(x0);
  factor_->set_scaled(*K.matrix(), h * h, K.pattern_id());
  const Eigen::VectorXd f0 = -potential_->gradient(x0);
  Eigen::VectorXd b = mass_dofs_.cwiseProduct(v) + h * f0;
  if (v_fixed.squaredNorm() > 0.0) b -= A * v_fixed + mass_dofs_.cwiseProduct(v_fixed);
  // A = M + h^2 K in K's own storage: rows and columns of fixed DOFs become identity rows. The
  // positions of the entries to clear and of the diagonal are found once per pattern and mask.
  const Factorization::Scatter& scatter = factor_->scatter(fixed, mass_dofs_);
  double* a_values = A.valuePtr();
  for (const int k : scatter.cleared) a_values[k] = 0.0;
  for (std::size_t i = 0; i < scatter.diagonal.size(); ++i)
    a_values[scatter.diagonal[i]] += scatter.diagonal_add[i];
  for (Eigen::Index i = 0; i < n; ++i)
    if (fixed[i]) b(i) = v_fixed(i);
  const FactorizationReuse& reuse = settings_.reuse;

  // The matrix of the current SQP iteration (A, or H from the second on) and the lagged
  // factorisation that solves with it.
  const Eigen::SparseMatrix<double>* current = &A;
  LaggedFactorization* F = &factor_->backward_euler;
  LaggedFactorization::Counters counters;
  // Whether the factorisation in use is kept for later matrices (then its columns P^-1 J_i^T are
  // worth caching). A Lagrangian Hessian changes in every SQP iteration, and solving with a
  // lagged one costs the splitting's CG solves (two or more per iteration) besides new
  // columns; where a factorisation costs fewer CG iterations than that
  // (`exact_lagrangian_below`, small meshes) H is factorised each time and W formed exactly.
  bool keep_factor = reuse.enabled;
  auto use = [&](const Eigen::SparseMatrix<double>& M, LaggedFactorization& slot) {
    current = &M;
    F = &slot;
    FactorizationReuse r = reuse;
    // (The cost is known from the slot's first factorisation on; that one is kept, as before.)
    if (&slot == &factor_->lagrangian && slot.refresh_cost() > 0.0 && slot.refresh_cost() < reuse.exact_lagrangian_below)
      r.enabled = false;
    keep_factor = r.enabled;
    F->use(M, r, counters, factor_->pattern);
  };
  auto solve = [&](const Eigen::VectorXd& r, Eigen::VectorXd& out, bool guess) { F->solve(r, out, guess, counters); };
  use(A, factor_->backward_euler);
  Eigen::VectorXd v_star;
  solve(b, v_star, false);

  // ---- SQP: linearise at x_k = x0 + h v_k and solve the subproblem
  //   min 1/2 (v - v*)^T A (v - v*)  s.t.  C(x_k) / h + J_k (v - v_k) >= 0 (+ friction),
  // whose solution is v = v_k + H^-1 (J^T lambda - g) with g = A (v_k - v*).
  const std::optional<EnergyLimit>& limit = settings_.energy_limit;
  Eigen::VectorXd v_k = v_star;
  // Multipliers of the previous LCP by constraint key; at the first SQP iteration those of the
  // previous step, which also give the first iteration's Lagrangian Hessian (SQP with initial
  // multiplier estimates: the converged step is the same, it is reached in fewer iterations).
  std::map<long, double> warm = multipliers_;
  std::map<long, char> ever_active;
  Eigen::SparseMatrix<double>& H = factor_->H;
  auto t_lcp = Clock::now();
  // The predictor: where the previous step showed the constraints' nonlinearity (two or more SQP
  // iterations, or an active energy limit), its constraint correction v - v* is the best guess of
  // this step's, so
  // the first linearisation is made at v* + that correction instead of v*: fewer SQP iterations
  // with the same acceptance test. v* itself is still tested first (energies and contacts only),
  // and taken as the step's answer when it satisfies the constraints, as without the predictor.
  const bool predict = settings_.sqp_predictor && settings_.sqp_max_iterations > 0 && predictor_.size() == n;
  bool predicted = false;  // v_k != v* (then the LCP's gradient term g = A (v_k - v*) is not zero)
  for (int k = 0;; ++k) {
    Eigen::VectorXd x_k = x0 + h * v_k;
    const bool check_only = k == 0 && predict;
    // v* is tested first on the elements whose limits were active (a failure there is the test's
    // answer), and on the whole mesh and the contacts only when they hold.
    Linearisation lin;
    if (check_only && active_limit_violated(*limited_, settings_, warm, x_k))
      lin.satisfied = false;
    else
      lin = linearise_constraints(*limited_, settings_, fixed, contacts_, time_, x_k, v_k, ever_active,
                                  k >= settings_.sqp_max_iterations || check_only);
    if (check_only && !lin.satisfied) {
      v_k = v_star + predictor_;
      for (Eigen::Index i = 0; i < n; ++i)
        if (fixed[i]) v_k(i) = v_star(i);
      x_k = x0 + h * v_k;
      predicted = true;
      // Rows also where the guess already satisfies the constraints: it is not the step's answer.
      lin = linearise_constraints(*limited_, settings_, fixed, contacts_, time_, x_k, v_k, ever_active, false, true);
    } else if (lin.satisfied || k >= settings_.sqp_max_iterations) {
      const double energy_violation = lin.energy_violation;
      report.energy_violation = std::max(0.0, energy_violation);
      report.penetration = lin.penetration;
      report.max_element_energy = lin.max_energy;
      report.converged = lin.satisfied;
      v = v_k;
      multipliers_ = k > 0 ? warm : std::map<long, double>{};
      break;
    }
    const std::vector<Row>& rows = lin.rows;
    report.energy_violation = std::max(0.0, lin.energy_violation);
    report.penetration = lin.penetration;
    report.max_element_energy = lin.max_energy;

    // ---- quadratic model: H = A plus the curvature of the energy constraints with lambda > 0
    bool stiffened = false;
    if (limit) {
      const int dofs = 3 * disc.nodes();
      std::vector<char> local_fixed(static_cast<size_t>(dofs));
      Eigen::MatrixXd& He = factor_->element_hessian;  // storage kept from element to element
      for (const auto& [key, lambda_e] : warm) {
        if (key < 0 || lambda_e <= 0.0) continue;  // contact rows are linear
        const std::vector<int>& slots = factor_->slots(disc, key);
        bool any_fixed = false, any_free = false;
        for (int a = 0; a < disc.nodes(); ++a)
          for (int i = 0; i < 3; ++i) {
            const bool f = fixed[static_cast<size_t>(3 * elements(key, a) + i)] != 0;
            local_fixed[static_cast<size_t>(3 * a + i)] = f ? 1 : 0;
            any_fixed = any_fixed || f;
            any_free = any_free || !f;
          }
        if (!any_free) continue;  // every entry has a fixed row or column
        if (!stiffened) {
          // H = A: same pattern (A holds every element block), so A's values are copied into H's
          // storage, kept from earlier steps.
          factor_->copy_a_into_h();
          stiffened = true;
        }
        // Entry (r, c) of the element block (element DOFs), scaled by h lambda_e / U_max as it is
        // added, where neither DOF is fixed.
        double* values = H.valuePtr();
        const double scale = h * lambda_e / limit->max_energy;
        auto add = [&](int r, int c, double value) {
          if (any_fixed && (local_fixed[static_cast<size_t>(r)] || local_fixed[static_cast<size_t>(c)])) return;
          values[slots[static_cast<size_t>(r * dofs + c)]] += value * scale;
        };
        limited_->element_hessian_into(key, x_k, He);
        for (int c = 0; c < dofs; ++c)
          for (int r = 0; r < dofs; ++r) add(r, c, He(r, c));
      }
    }
    if (stiffened) {
      use(H, factor_->lagrangian);
    } else if (current != &A) {
      use(A, factor_->backward_euler);
    }
    Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
    if (k > 0 || predicted) factor_->multiply_a(v_k - v_star, g);

    // ---- LCP (Eq. 23) with W = J H^-1 J^T
    const Eigen::Index m = static_cast<Eigen::Index>(rows.size());
    Eigen::VectorXd offset(m), lambda(m);
    std::vector<LcpRow> bounds(m);
    for (Eigen::Index i = 0; i < m; ++i) {
      offset(i) = rows[i].offset;
      bounds[i] = rows[i].bounds;
      const auto w = warm.find(rows[i].key);
      lambda(i) = w == warm.end() ? 0.0 : w->second;
    }
    Eigen::SparseMatrix<double, Eigen::RowMajor> J;
    set_rows(J, m, n, [&](Eigen::Index i) -> const auto& { return rows[static_cast<size_t>(i)].jacobian; });
    // W~ = J~ P^-1 J~^T from the factorisation at hand. Columns P^-1 J_i^T are cached per
    // constraint with the Jacobian J~_i they were computed for and reused while J_i stays close
    // (contact rows against a fixed normal do not change at all); new ones come from one
    // multi-RHS solve. W~ is exact when the factorisation is of H and every J~_i = J_i.
    Eigen::MatrixXd W, Y;  // W~ and its columns P^-1 J~^T
    bool w_exact = false;
    auto form_w = [&](bool reuse_columns) {
      const auto t_w = Clock::now();
      if (!keep_factor && F->exact()) {
        // The factorisation is of the current matrix and is not kept: W exactly, no columns.
        W = F->gram(J);
        Y.resize(0, 0);
        w_exact = true;
        for (Eigen::Index i = 0; i < m; ++i) W(i, i) = std::max(W(i, i), 1e-14 * W.diagonal().cwiseAbs().maxCoeff());
        report.w_seconds += since(t_w);
        return;
      }
      std::vector<Eigen::Index> missing;
      w_exact = F->exact();
      for (Eigen::Index i = 0; i < m; ++i) {
        const auto it = F->columns().find(rows[i].key);
        if (it != F->columns().end() && it->second.jacobian.size() == rows[i].jacobian.size()) {
          double diff = 0.0, norm = 0.0;
          bool same_dofs = true;
          for (std::size_t j = 0; j < rows[i].jacobian.size(); ++j) {
            same_dofs = same_dofs && it->second.jacobian[j].first == rows[i].jacobian[j].first;
            diff += std::pow(it->second.jacobian[j].second - rows[i].jacobian[j].second, 2);
            norm += std::pow(rows[i].jacobian[j].second, 2);
          }
          if (same_dofs && diff == 0.0) continue;
          if (same_dofs && reuse_columns && diff <= std::pow(reuse.column_reuse_tolerance, 2) * norm) {
            w_exact = false;
            continue;
          }
        }
        missing.push_back(i);
      }
      if (!missing.empty()) {
        Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, static_cast<Eigen::Index>(missing.size()));
        for (std::size_t c = 0; c < missing.size(); ++c)
          for (const auto& [dof, value] : rows[missing[c]].jacobian) rhs(dof, static_cast<Eigen::Index>(c)) = value;
        const Eigen::MatrixXd cols = F->apply_inverse(rhs);
        for (std::size_t c = 0; c < missing.size(); ++c)
          F->columns()[rows[missing[c]].key] = {rows[missing[c]].jacobian, cols.col(static_cast<Eigen::Index>(c))};
      }
      Y.resize(n, m);
      for (Eigen::Index i = 0; i < m; ++i) Y.col(i) = F->columns().at(rows[i].key).values;
      Eigen::SparseMatrix<double, Eigen::RowMajor> Jc;
      set_rows(Jc, m, n, [&](Eigen::Index i) -> const auto& { return F->columns().at(rows[i].key).jacobian; });
      W = Jc * Y;  // sparse-times-dense: O(nnz(J) m)
      for (Eigen::Index i = 0; i < m; ++i) W(i, i) = std::max(W(i, i), 1e-14 * W.diagonal().cwiseAbs().maxCoeff());
      // Bound the cache (n doubles per column) on large meshes.
      if (static_cast<double>(F->columns().size()) * static_cast<double>(n) > 3.2e7) F->columns().clear();
      report.w_seconds += since(t_w);
    };
    form_w(true);
    // Splitting iteration: w(lambda) = offset + J u(lambda), u = H^-1 (J^T lambda - g) exactly;
    // PGS on W~ with q~ = w(lambda_s) - W~ lambda_s. With an exact W~ one PGS solve is the answer.
    // It stops when the exact LCP residual is below 1 % of the SQP's constraint tolerances
    // (as velocities: a residual r moves the end-of-step constraint by h r), or the PGS
    // tolerance if that is looser; the PGS inner solves use half of it.
    const double split_tolerance = std::max(
        settings_.pgs.tolerance, 0.01 * std::min(settings_.contact_tolerance, settings_.energy_tolerance) / h);
    PgsSettings inner = settings_.pgs;
    inner.tolerance = 0.5 * split_tolerance;
    Eigen::VectorXd u = Eigen::VectorXd::Zero(n), w(m), lambda_before = lambda;
    double residual = 0.0, previous_residual = 0.0;
    bool pgs_on_exact_w = false;
    for (int s = 0;; ++s) {
      const bool was_exact = F->exact();
      const int cg_before = counters.cg_iterations;
      // After a PGS solve, the change of multipliers moves u by about P^-1 J^T dlambda: with that
      // as the starting guess CG only corrects for P != H.
      if (s > 0 && Y.size() > 0) u.noalias() += Y * (lambda - lambda_before);
      solve(Eigen::VectorXd(J.transpose() * lambda) - g, u, s > 0);
      const int cg_this_split = counters.cg_iterations - cg_before;
      if (F->exact() && !was_exact) form_w(false);  // CG gave up and H was refactorised: W is exact now
      w = offset + J * u;
      residual = lcp_residual(W, w - W * lambda, bounds, lambda);
      if (residual <= split_tolerance || pgs_on_exact_w) break;
      // Give up on a slow splitting (refactorise and form W exactly) when the sweeps still
      // needed, extrapolated from the last contraction, would cost more CG than a factorisation.
      bool slow = s >= reuse.max_splitting_iterations;
      if (!slow && !F->exact() && s >= 2) {
        const double rate = residual / previous_residual;
        const double remaining = rate >= 1.0 ? 1e9 : std::log(split_tolerance / residual) / std::log(rate);
        slow = remaining * std::max(cg_this_split, 1) > F->refresh_cost();
      }
      previous_residual = residual;
      if (slow) {
        if (!F->exact()) F->refactor(counters);
        form_w(false);
      }
      pgs_on_exact_w = w_exact;
      const auto t_pgs = Clock::now();
      lambda_before = lambda;
      const PgsReport pgs = solve_pgs(W, w - W * lambda, bounds, lambda, inner);
      report.pgs_seconds += since(t_pgs);
      ++report.splitting_iterations;
      report.pgs_iterations += pgs.iterations;
      report.pgs_unconverged += pgs.converged ? 0 : 1;
    }
    report.sqp_iterations = k + 1;
    report.pgs_residual = residual;
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
    v_k += u;  // Eq. 21 for k = 0
  }
  report.lcp_seconds = since(t_lcp);
  // The next step's predictor: this step's correction, where the constraints' nonlinearity
  // showed (two or more SQP iterations, or an active energy limit). Contacts alone are linear in
  // the positions (a plane's exactly): one iteration answers them, a guess would only cost.
  // Where the step before left a correction too, half of their difference is added (a damped
  // linear extrapolation): while the same limits stay active the correction follows the motion
  // smoothly, and the first linearisation's error is quadratic in the distance from the guess to
  // the answer. Measured over paper 001's beams and spheres, the full extrapolation
  // (2 c_n - c_n-1) saved as many SQP iterations on the beams but cost some on the spheres, whose
  // impacts change the correction abruptly; half of it saves 12-17 % on the beams and leaves the
  // spheres within 1-2 % (docs/performance.md).
  if (report.sqp_iterations >= 2 || (report.sqp_iterations >= 1 && report.active_energy > 0)) {
    Eigen::VectorXd correction = v - v_star;
    if (settings_.sqp_extrapolation && correction_.size() == n)
      predictor_ = 1.5 * correction - 0.5 * correction_;
    else
      predictor_ = correction;
    correction_ = std::move(correction);
  } else {
    predictor_.resize(0);
    correction_.resize(0);
  }
  report.factorizations = counters.factorizations;
  report.cg_iterations = counters.cg_iterations;
  report.factor_seconds = counters.factor_seconds;
  report.solve_seconds = counters.solve_seconds;
  // Prescribed DOFs end exactly where their motion puts them (the solves above hold them only to
  // the CG tolerance).
  for (Eigen::Index i = 0; i < n; ++i)
    if (fixed[i]) v(i) = v_fixed(i);
  x = x0 + h * v;
  for (Eigen::Index i = 0; i < n; ++i)
    if (fixed[i]) x(i) = x_end(i);
  time_ += h;
  report.seconds = since(t_step);
  return report;
}

}  // namespace sinew
