// Paper 001 §5-6: the constrained backward-Euler step on the beam and the falling sphere.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

#include <fmt/format.h>

#include "sinew/forms/corotational_hex_form.hpp"
#include "sinew/forms/external_force_form.hpp"
#include "experiments/paper001_experiments.hpp"
#include "sinew/element/mass.hpp"
#include "sinew/mesh/lattice.hpp"

namespace sinew {
namespace {

using namespace paper001;

// A cantilever of 4 hexahedra under gravity, fixed at x = 0 (density 100): the stepper tests'
// small beam.
struct Cantilever {
  VolumeMesh mesh = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0.2, 0.2), Eigen::Vector3i(4, 1, 1));
  std::shared_ptr<Discretization> disc = std::make_shared<Discretization>(mesh);
  HookeCoefficients hooke = HookeCoefficients::from_young_poisson(1e5, 0.3);
  std::shared_ptr<CorotationalHexForm> model = std::make_shared<CorotationalHexForm>(disc, hooke);
  Eigen::VectorXd masses = lumped_mass(*disc, 100.0);
  Eigen::Index n = 3 * mesh.num_vertices();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  std::vector<char> fixed = std::vector<char>(static_cast<size_t>(n), 0);
  int wall = -1, tip = -1;  // a vertex at x = 0 and one at x = 1

  Cantilever() {
    for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) {
      f(3 * v + 2) = -9.81 * masses(v);
      if (mesh.vertices(v, 0) < 1e-9) fixed[3 * v] = fixed[3 * v + 1] = fixed[3 * v + 2] = 1;
      if (mesh.vertices(v, 0) < 1e-9 && wall < 0) wall = static_cast<int>(v);
      if (mesh.vertices(v, 0) > 1.0 - 1e-9) tip = static_cast<int>(v);
    }
  }
};

TEST(Paper001Meshes, BeamAndSphereHaveThePapersElementCounts) {
  const VolumeMesh beam = beam_mesh();
  EXPECT_EQ(beam.num_elements(), 56);
  EXPECT_NEAR(beam.vertices.col(0).maxCoeff() - beam.vertices.col(0).minCoeff(), 1.0, 1e-12);
  EXPECT_NEAR(beam.vertices.col(1).maxCoeff() - beam.vertices.col(1).minCoeff(), 0.12, 1e-12);
  const VolumeMesh sphere = sphere_mesh(Eigen::Vector3d::Zero(), 1.0, 3);
  EXPECT_EQ(sphere.num_elements(), 27);
  for (Eigen::Index v = 0; v < sphere.num_vertices(); ++v) EXPECT_LE(sphere.vertices.row(v).norm(), 1.0 + 1e-12);
}

TEST(EnergyLimitedStepper, FreeFallWithoutConstraintsIsBackwardEuler) {
  // A rigid free fall has no elastic force: v = v0 + h g exactly, every step.
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), Eigen::Vector3i(1, 1, 1));
  auto model = std::make_shared<CorotationalHexForm>(std::make_shared<Discretization>(mesh),
                                                 HookeCoefficients::from_young_poisson(1e5, 0.3));
  const Eigen::VectorXd masses = lumped_mass(model->discretization(), 100.0);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(24);
  for (int v = 0; v < 8; ++v) f(3 * v + 2) = -9.81 * masses(v);
  EnergyLimitedStepSettings s;
  s.time_step = 0.02;
  EnergyLimitedStepper stepper(model, masses, f, std::vector<char>(24, 0), {}, s);
  Eigen::VectorXd x = mesh.rest_positions(), v = Eigen::VectorXd::Zero(24);
  for (int k = 1; k <= 5; ++k) {
    const EnergyLimitedStepReport r = stepper.step(x, v);
    EXPECT_TRUE(r.converged);
    EXPECT_EQ(r.sqp_iterations, 0);
    for (int i = 0; i < 8; ++i) EXPECT_NEAR(v(3 * i + 2), -9.81 * 0.02 * k, 1e-9);
  }
}

TEST(EnergyLimitedStepper, PredictedStepTestsVStarOnTheActiveElementsFirstButTakesItWhenItHolds) {
  // A step with a predictor tests v* on the elements with active rows first (a violation there
  // answers the test) and on the whole mesh only when they hold. A cantilever's first step from
  // rest strains the wall element most and the tip element least; the limit lies between them.
  const Cantilever c;
  const auto& [mesh, disc, hooke, model, masses, n, f, fixed, wall, tip] = c;
  auto step_once = [&](double limit, std::map<long, double> multipliers, bool predict) {
    EnergyLimitedStepSettings s;
    s.energy_limit = EnergyLimit{limit};
    EnergyLimitedStepper stepper(model, masses, f, fixed, {}, s);
    stepper.set_multipliers(std::move(multipliers));
    if (predict) stepper.set_predictor(Eigen::VectorXd::Constant(n, 0.01));
    Eigen::VectorXd x = mesh.rest_positions(), v = Eigen::VectorXd::Zero(n);
    const EnergyLimitedStepReport r = stepper.step(x, v);
    return std::make_tuple(r, x, v);
  };
  // The unconstrained step (no limit reached): its element energies.
  const auto [free, x_free, v_free] = step_once(1e6, {}, false);
  ASSERT_EQ(free.sqp_iterations, 0);
  std::vector<double> energies;
  model->element_values(x_free, energies);
  const auto e_high = std::max_element(energies.begin(), energies.end()) - energies.begin();
  const auto e_low = std::min_element(energies.begin(), energies.end()) - energies.begin();
  ASSERT_GT(energies[static_cast<size_t>(e_high)], 100.0 * energies[static_cast<size_t>(e_low)]);
  const double between = std::sqrt(energies[static_cast<size_t>(e_high)] * energies[static_cast<size_t>(e_low)]);

  // v* holds: a predicted step takes it, bit for bit, whatever its active rows.
  const auto [held, x_held, v_held] = step_once(1e6, {{e_high, 1.0}, {e_low, 2.0}}, true);
  EXPECT_EQ(held.sqp_iterations, 0);
  EXPECT_EQ(v_held, v_free);
  EXPECT_EQ(x_held, x_free);
  // v* violates the limit on an element without an active row: the whole mesh is tested and the
  // step is solved, within the limit.
  const auto [solved, x_solved, v_solved] = step_once(between, {{e_low, 1.0}}, true);
  EXPECT_GE(solved.sqp_iterations, 1);
  EXPECT_TRUE(solved.converged);
  EXPECT_LE(solved.max_element_energy, between * (1.0 + 1e-3));
  // ... and on one with an active row: likewise.
  const auto [early, x_early, v_early] = step_once(between, {{e_high, 1.0}}, true);
  EXPECT_GE(early.sqp_iterations, 1);
  EXPECT_TRUE(early.converged);
  EXPECT_LE(early.max_element_energy, between * (1.0 + 1e-3));
}

TEST(EnergyLimitedStepper, BeamDeflectionFallsWithTheEnergyLimitAndLimitsHold) {
  // Fig. 3: linear 150 kPa, limited 1.0 / 0.5 / 0.1 J, linear 2 MPa.
  struct Case {
    const char* name;
    double young;
    std::optional<double> limit;
  };
  const std::vector<Case> cases = {{"linear 150 kPa", 150e3, {}},
                                   {"150 kPa, U_e <= 1.0 J", 150e3, 1.0},
                                   {"150 kPa, U_e <= 0.5 J", 150e3, 0.5},
                                   {"150 kPa, U_e <= 0.1 J", 150e3, 0.1},
                                   {"linear 2 MPa", 2e6, {}}};
  std::vector<double> deflection;
  for (const Case& c : cases) {
    BeamConfig config;
    config.young = c.young;
    config.max_energy = c.limit;
    config.duration = 1.5;
    const BeamResult r = run_beam(config);
    fmt::print("beam {:<24} max tip deflection {:.4f} m, max U_e {:.4f} J, SQP {} PGS {} unconverged {} ({:.2f} ms/step)\n",
               c.name, r.max_tip_deflection, r.totals.max_element_energy, r.totals.sqp_iterations,
               r.totals.pgs_iterations, r.totals.unconverged_steps, r.totals.ms_per_step());
    deflection.push_back(r.max_tip_deflection);
    if (c.limit) {
      EXPECT_EQ(r.totals.unconverged_steps, 0) << c.name;
      EXPECT_LE(r.totals.max_element_energy, *c.limit * (1.0 + config.solver.energy_tolerance)) << c.name;
    }
  }
  for (size_t i = 1; i < deflection.size(); ++i) EXPECT_LT(deflection[i], deflection[i - 1]) << cases[i].name;
}

TEST(EnergyLimitedStepper, FallingSphereRestsOnFrictionalGround) {
  // Fig. 4 (27 hexahedra): all three land without penetration beyond tolerance; the energy
  // limit keeps the compliant sphere from being compressed as much as the linear one.
  struct Case {
    const char* name;
    double young;
    std::optional<double> limit;
  };
  std::vector<SphereResult> results;
  for (const Case& c : {Case{"linear 150 kPa", 150e3, {}}, Case{"linear 1 MPa", 1e6, {}},
                        Case{"150 kPa, U_e <= 500 J", 150e3, 500.0}}) {
    SphereConfig config;
    config.young = c.young;
    config.max_energy = c.limit;
    config.duration = 2.0;
    const SphereResult r = run_falling_sphere(config);
    fmt::print("sphere {:<24} peak compression {:.1f} %, rebound {:.3f} m, max U_e {:.1f} J, penetration {:.2e} m, "
               "SQP {} PGS {} unconverged {} ({:.2f} ms/step)\n",
               c.name, 100 * r.peak_compression, r.rebound_height, r.totals.max_element_energy, r.max_penetration,
               r.totals.sqp_iterations, r.totals.pgs_iterations, r.totals.unconverged_steps, r.totals.ms_per_step());
    EXPECT_EQ(r.totals.unconverged_steps, 0) << c.name;
    EXPECT_LE(r.max_penetration, config.solver.contact_tolerance) << c.name;
    EXPECT_GT(r.peak_compression, 0.0) << c.name;
    results.push_back(r);
  }
  EXPECT_LT(results[1].peak_compression, results[0].peak_compression);
  EXPECT_LT(results[2].peak_compression, results[0].peak_compression);
  EXPECT_LE(results[2].totals.max_element_energy, 500.0 * (1.0 + SphereConfig{}.solver.energy_tolerance));
}

}  // namespace
// A form without energy that couples two vertices: it adds blocks to the Hessian's pattern
// and nothing to its values.
class ZeroCouplingForm final : public Form {
 public:
  ZeroCouplingForm(int a, int b) : a_(a), b_(b) {}
  std::string name() const override { return "zero-coupling"; }
  double value(const Eigen::VectorXd&) const override { return 0.0; }
  void add_gradient(const Eigen::VectorXd&, Eigen::VectorXd&) const override {}
  void add_hessian(const Eigen::VectorXd&, BlockHessian&) const override {}
  void couplings(std::vector<std::vector<int>>& cliques) const override { cliques.push_back({a_, b_}); }

 private:
  int a_, b_;
};

TEST(EnergyLimitedStepper, StepsAfterTheHessianPatternChangesMatchAStepperBuiltWithIt) {
  // The stepper keeps the step matrix's storage, the element slots of the Lagrangian Hessian and
  // its pattern from step to step: when the potential's Hessian pattern changes (a form with new
  // couplings added between steps), it must take the new one. A cantilever with active energy
  // limits (from the sixth step on), the pattern widened after 7 steps, against a stepper that had
  // the coupling throughout.
  const Cantilever c;
  const auto& [mesh, disc, hooke, model, masses, n, f, fixed, wall, tip] = c;
  EnergyLimitedStepSettings s;
  s.energy_limit = EnergyLimit{0.05};
  auto run = [&](bool coupled_from_start) {
    auto potential = std::make_shared<Problem>(mesh.num_vertices());
    potential->add_form(model);
    potential->add_form(std::make_shared<ExternalForceForm>(f));
    if (coupled_from_start) potential->add_form(std::make_shared<ZeroCouplingForm>(wall, tip));
    EnergyLimitedStepper stepper(potential, model, masses, {}, s);
    Eigen::VectorXd x = mesh.rest_positions(), v = Eigen::VectorXd::Zero(n);
    int active_after_change = 0;
    for (int k = 0; k < 10; ++k) {
      if (k == 7 && !coupled_from_start) potential->add_form(std::make_shared<ZeroCouplingForm>(wall, tip));
      const Eigen::VectorXd x_end = x;
      const EnergyLimitedStepReport r = stepper.step(x, v, fixed, x_end);
      EXPECT_TRUE(r.converged);
      if (k >= 7) active_after_change += r.active_energy;
    }
    return std::make_tuple(x, v, active_after_change);
  };
  const auto [x_changed, v_changed, active_changed] = run(false);
  const auto [x_coupled, v_coupled, active_coupled] = run(true);
  EXPECT_GT(active_changed, 0);  // the Lagrangian Hessian was built after the change
  EXPECT_EQ(active_changed, active_coupled);
  EXPECT_LE((x_changed - x_coupled).norm(), 1e-8 * x_coupled.norm());
  EXPECT_LE((v_changed - v_coupled).norm(), 1e-5 * v_coupled.norm());
}

// The corotational form seen only as an ElementForm (the stepper's generic path for element
// Hessians).
class GenericElementForm final : public ElementForm {
 public:
  explicit GenericElementForm(std::shared_ptr<const CorotationalHexForm> form) : form_(std::move(form)) {}
  std::string name() const override { return "generic"; }
  const Discretization& discretization() const override { return form_->discretization(); }
  double element_value(Eigen::Index e, const Eigen::VectorXd& x) const override { return form_->element_value(e, x); }
  void element_values(const Eigen::VectorXd& x, std::vector<double>& energies) const override {
    form_->element_values(x, energies);
  }
  Eigen::VectorXd element_gradient(Eigen::Index e, const Eigen::VectorXd& x, JacobianKind kind) const override {
    return form_->element_gradient(e, x, kind);
  }
  bool supports(JacobianKind kind) const override { return form_->supports(kind); }
  Eigen::MatrixXd element_hessian(Eigen::Index e, const Eigen::VectorXd& x) const override {
    return form_->element_hessian(e, x);
  }
  double value(const Eigen::VectorXd& x) const override { return form_->value(x); }
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override { form_->add_gradient(x, g); }
  void add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const override { form_->add_hessian(x, H); }

 private:
  std::shared_ptr<const CorotationalHexForm> form_;
};

TEST(EnergyLimitedStepper, CorotationalLagrangianBlocksAreTheElementHessiansBitForBit) {
  // The stepper adds a corotational element's Lagrangian Hessian block from the form's node-pair
  // kernel; through the generic ElementForm path (element_hessian) the motion must be the same
  // bit for bit. A cantilever with active limits, also on the elements at the fixed wall.
  const Cantilever c;
  const auto& [mesh, disc, hooke, model, masses, n, f, fixed, wall, tip] = c;
  EnergyLimitedStepSettings s;
  s.energy_limit = EnergyLimit{0.02};
  auto run = [&](bool generic) {
    // A model of its own: its rotation cache warm-starts the polar decompositions.
    auto own = std::make_shared<CorotationalHexForm>(disc, hooke);
    std::shared_ptr<const ElementForm> limited = own;
    if (generic) limited = std::make_shared<GenericElementForm>(own);
    auto potential = std::make_shared<Problem>(mesh.num_vertices());
    potential->add_form(own);
    potential->add_form(std::make_shared<ExternalForceForm>(f));
    EnergyLimitedStepper stepper(potential, limited, masses, {}, s);
    Eigen::VectorXd x = mesh.rest_positions(), v = Eigen::VectorXd::Zero(n);
    int sqp = 0;
    std::set<long> active;
    for (int k = 0; k < 12; ++k) {
      const Eigen::VectorXd x_end = x;
      sqp += stepper.step(x, v, fixed, x_end).sqp_iterations;
      for (const auto& [key, lambda] : stepper.multipliers())
        if (lambda > 0.0) active.insert(key);
    }
    return std::make_tuple(x, v, sqp, active);
  };
  const auto [x_kernel, v_kernel, sqp_kernel, active_kernel] = run(false);
  const auto [x_generic, v_generic, sqp_generic, active_generic] = run(true);
  EXPECT_EQ(active_kernel.count(0), 1u);  // the element at the wall was limited
  EXPECT_GE(active_kernel.size(), 2u);
  EXPECT_EQ(sqp_kernel, sqp_generic);
  EXPECT_TRUE(x_kernel == x_generic);
  EXPECT_TRUE(v_kernel == v_generic);
}

TEST(EnergyLimitedStepper, FactorizationReuseMatchesFreshFactorizations) {
  // Reusing a lagged factorisation (CG preconditioner + LCP splitting) must land on the same
  // motion as factorising every matrix, up to the solver tolerances, with far fewer
  // factorisations. Sphere at 6 cells (energy limits and frictional contact both active) and the
  // beam (fixed end, large rotations).
  SphereConfig sphere;
  sphere.cells = 6;
  sphere.young = 500e3;
  sphere.max_energy = 100.0 * std::pow(9.0 / 6.0, 3);  // the bench's limit scaled to the element volume
  sphere.duration = 1.5;
  SphereConfig fresh_sphere = sphere;
  fresh_sphere.solver.reuse.enabled = false;
  const SphereResult a = run_falling_sphere(fresh_sphere), b = run_falling_sphere(sphere);
  fmt::print("sphere 6 cells: fresh {} factorisations, reuse {} factorisations + {} CG, {} splitting sweeps; "
             "compression {:.5f} / {:.5f}, rebound {:.5f} / {:.5f}, max active energy rows {} / {}\n",
             a.totals.factorizations, b.totals.factorizations, b.totals.cg_iterations, b.totals.splitting_iterations,
             a.peak_compression, b.peak_compression, a.rebound_height, b.rebound_height, a.totals.max_active_energy,
             b.totals.max_active_energy);
  EXPECT_GT(a.totals.max_active_energy, 0);
  EXPECT_GT(a.totals.max_active_contacts, 0);
  EXPECT_EQ(b.totals.unconverged_steps, 0);
  EXPECT_LT(b.totals.factorizations, a.totals.factorizations / 3);
  EXPECT_GT(b.totals.cg_iterations, 0);
  EXPECT_NEAR(b.peak_compression, a.peak_compression, 1e-3);
  EXPECT_NEAR(b.rebound_height, a.rebound_height, 1e-3);
  EXPECT_LE(b.max_penetration, sphere.solver.contact_tolerance);
  EXPECT_LE(b.totals.max_element_energy, *sphere.max_energy * (1.0 + sphere.solver.energy_tolerance));

  BeamConfig beam;
  beam.max_energy = 0.1;
  beam.duration = 1.0;
  BeamConfig fresh_beam = beam;
  fresh_beam.solver.reuse.enabled = false;
  const BeamResult c = run_beam(fresh_beam), d = run_beam(beam);
  fmt::print("beam U_e <= 0.1 J: fresh {} factorisations, reuse {} + {} CG; tip deflection {:.6f} / {:.6f} m\n",
             c.totals.factorizations, d.totals.factorizations, d.totals.cg_iterations, c.max_tip_deflection,
             d.max_tip_deflection);
  EXPECT_EQ(d.totals.unconverged_steps, 0);
  EXPECT_LT(d.totals.factorizations, c.totals.factorizations);
  EXPECT_NEAR(d.max_tip_deflection, c.max_tip_deflection, 1e-3 * c.max_tip_deflection);
  EXPECT_LE(d.totals.max_element_energy, 0.1 * (1.0 + beam.solver.energy_tolerance));
}

TEST(EnergyLimitedStepper, FactorisedLagrangianHessiansGiveTheLaggedOnesMotion) {
  // On the beam a factorisation costs ~5 CG iterations (below `exact_lagrangian_below`), so each
  // Lagrangian Hessian is factorised and W = J H^-1 J^T formed exactly (forward substitutions):
  // one PGS solve per SQP iteration. Forcing lagged Hessians (CG + splitting) must give the same
  // motion up to the CG and LCP tolerances.
  BeamConfig beam;
  beam.max_energy = 0.5;
  beam.duration = 1.0;
  BeamConfig lagged = beam;
  lagged.solver.reuse.exact_lagrangian_below = 0.0;
  const BeamResult a = run_beam(lagged), b = run_beam(beam);
  fmt::print("beam U_e <= 0.5 J: lagged H {} factorisations + {} CG, {} SQP, {} sweeps; factorised H {} + {} CG, {} SQP, "
             "{} sweeps; tip deflection {:.7f} / {:.7f} m\n",
             a.totals.factorizations, a.totals.cg_iterations, a.totals.sqp_iterations, a.totals.splitting_iterations,
             b.totals.factorizations, b.totals.cg_iterations, b.totals.sqp_iterations, b.totals.splitting_iterations,
             a.max_tip_deflection, b.max_tip_deflection);
  EXPECT_GT(b.totals.max_active_energy, 0);
  EXPECT_EQ(b.totals.unconverged_steps, 0);
  EXPECT_GT(a.totals.splitting_iterations, a.totals.sqp_iterations);
  EXPECT_LE(b.totals.splitting_iterations, b.totals.sqp_iterations);
  EXPECT_LT(b.totals.cg_iterations, a.totals.cg_iterations);
  EXPECT_NEAR(b.max_tip_deflection, a.max_tip_deflection, 1e-4 * a.max_tip_deflection);
  EXPECT_LE(b.totals.max_element_energy, 0.5 * (1.0 + beam.solver.energy_tolerance));
}

TEST(EnergyLimitedStepper, LaggedSolvesFallBackToRefactorisation) {
  // With a CG budget of one iteration a lagged factorisation can only finish a solve when it is
  // of the very same matrix (free fall: no rotation); every other solve must fall back to a
  // fresh factorisation and give the fresh-factorisation answer. Lagrangian Hessians lagged too
  // (on this sphere they are otherwise factorised each time: exact_lagrangian_below).
  SphereConfig config;
  config.max_energy = 500.0;
  config.duration = 1.2;
  config.solver.reuse.exact_lagrangian_below = 0.0;
  SphereConfig starved = config;
  starved.solver.reuse.max_cg_iterations = 1;
  starved.solver.reuse.cg_tolerance = 1e-14;
  SphereConfig fresh = config;
  fresh.solver.reuse.enabled = false;
  const SphereResult a = run_falling_sphere(fresh), b = run_falling_sphere(starved), c = run_falling_sphere(config);
  EXPECT_EQ(b.totals.unconverged_steps, 0);
  EXPECT_GT(b.totals.factorizations, 2 * c.totals.factorizations);
  EXPECT_LE(b.totals.cg_iterations, b.totals.steps + b.totals.sqp_iterations + b.totals.splitting_iterations);
  EXPECT_NEAR(b.peak_compression, a.peak_compression, 1e-6);
  EXPECT_NEAR(b.rebound_height, a.rebound_height, 1e-6);
}

TEST(EnergyLimitedStepper, BlockFactorOfSmallMatricesGivesCholmodsMotion) {
  // The beam's and the sphere's matrices (56 and 27 hexahedra) are factorised on 3x3 vertex
  // blocks (BlockCholesky); forcing CHOLMOD everywhere (block_factorization_below = 0) must give the same
  // motion up to the CG and LCP tolerances, with the limits and contacts held.
  SphereConfig sphere;
  sphere.max_energy = 500.0;
  sphere.duration = 1.5;
  SphereConfig sphere_cholmod = sphere;
  sphere_cholmod.solver.reuse.block_factorization_below = 0;
  const SphereResult a = run_falling_sphere(sphere_cholmod), b = run_falling_sphere(sphere);
  fmt::print("sphere U_e <= 500 J: CHOLMOD {} factorisations + {} CG, blocks {} + {}; compression {:.6f} / {:.6f}, "
             "rebound {:.6f} / {:.6f}\n",
             a.totals.factorizations, a.totals.cg_iterations, b.totals.factorizations, b.totals.cg_iterations,
             a.peak_compression, b.peak_compression, a.rebound_height, b.rebound_height);
  EXPECT_GT(b.totals.max_active_energy, 0);
  EXPECT_GT(b.totals.max_active_contacts, 0);
  EXPECT_EQ(b.totals.unconverged_steps, 0);
  EXPECT_NEAR(b.peak_compression, a.peak_compression, 1e-4);
  EXPECT_NEAR(b.rebound_height, a.rebound_height, 1e-4);
  EXPECT_LE(b.max_penetration, sphere.solver.contact_tolerance);
  EXPECT_LE(b.totals.max_element_energy, 500.0 * (1.0 + sphere.solver.energy_tolerance));

  BeamConfig beam;
  beam.max_energy = 0.5;
  beam.duration = 1.0;
  BeamConfig beam_cholmod = beam;
  beam_cholmod.solver.reuse.block_factorization_below = 0;
  const BeamResult c = run_beam(beam_cholmod), d = run_beam(beam);
  fmt::print("beam U_e <= 0.5 J: CHOLMOD {} factorisations + {} CG, blocks {} + {}; tip deflection {:.7f} / {:.7f} m\n",
             c.totals.factorizations, c.totals.cg_iterations, d.totals.factorizations, d.totals.cg_iterations,
             c.max_tip_deflection, d.max_tip_deflection);
  EXPECT_GT(d.totals.max_active_energy, 0);
  EXPECT_EQ(d.totals.unconverged_steps, 0);
  EXPECT_NEAR(d.max_tip_deflection, c.max_tip_deflection, 1e-4 * c.max_tip_deflection);
  EXPECT_LE(d.totals.max_element_energy, 0.5 * (1.0 + beam.solver.energy_tolerance));
}

TEST(EnergyLimitedStepper, SqpPredictorGivesTheSameMotionInFewerIterations) {
  // The predictor linearises a step first at v* plus the previous step's correction v - v*
  // (where that step showed the energy limits' nonlinearity). Same acceptance test, so the same
  // motion up to the SQP tolerances, in fewer SQP iterations; contact-only steps are untouched.
  BeamConfig beam;
  beam.max_energy = 0.5;
  beam.duration = 1.0;
  BeamConfig beam_plain = beam;
  beam_plain.solver.sqp_predictor = false;
  const BeamResult a = run_beam(beam_plain), b = run_beam(beam);
  fmt::print("beam U_e <= 0.5 J: without predictor {} SQP, {} factorisations, tip deflection {:.7f} m; with {} SQP, {}, "
             "{:.7f} m\n",
             a.totals.sqp_iterations, a.totals.factorizations, a.max_tip_deflection, b.totals.sqp_iterations,
             b.totals.factorizations, b.max_tip_deflection);
  EXPECT_GT(b.totals.max_active_energy, 0);
  EXPECT_EQ(b.totals.unconverged_steps, 0);
  EXPECT_LT(b.totals.sqp_iterations, a.totals.sqp_iterations * 3 / 4);
  EXPECT_LT(b.totals.factorizations, a.totals.factorizations);
  EXPECT_NEAR(b.max_tip_deflection, a.max_tip_deflection, 1e-4 * a.max_tip_deflection);
  EXPECT_LE(b.totals.max_element_energy, 0.5 * (1.0 + beam.solver.energy_tolerance));

  SphereConfig sphere;
  sphere.max_energy = 500.0;
  sphere.duration = 1.5;
  SphereConfig sphere_plain = sphere;
  sphere_plain.solver.sqp_predictor = false;
  const SphereResult c = run_falling_sphere(sphere_plain), d = run_falling_sphere(sphere);
  fmt::print("sphere U_e <= 500 J: without predictor {} SQP, compression {:.6f}, rebound {:.6f}; with {} SQP, {:.6f}, "
             "{:.6f}\n",
             c.totals.sqp_iterations, c.peak_compression, c.rebound_height, d.totals.sqp_iterations, d.peak_compression,
             d.rebound_height);
  EXPECT_GT(d.totals.max_active_energy, 0);
  EXPECT_GT(d.totals.max_active_contacts, 0);
  EXPECT_EQ(d.totals.unconverged_steps, 0);
  EXPECT_LT(d.totals.sqp_iterations, c.totals.sqp_iterations);
  EXPECT_NEAR(d.peak_compression, c.peak_compression, 1e-3);
  EXPECT_NEAR(d.rebound_height, c.rebound_height, 1e-3);
  EXPECT_LE(d.max_penetration, sphere.solver.contact_tolerance);
  EXPECT_LE(d.totals.max_element_energy, 500.0 * (1.0 + sphere.solver.energy_tolerance));

  SphereConfig linear;  // contacts only: no prediction, the very same steps
  linear.duration = 1.5;
  SphereConfig linear_plain = linear;
  linear_plain.solver.sqp_predictor = false;
  const SphereResult e = run_falling_sphere(linear_plain), f = run_falling_sphere(linear);
  EXPECT_EQ(f.totals.sqp_iterations, e.totals.sqp_iterations);
  EXPECT_EQ(f.totals.pgs_iterations, e.totals.pgs_iterations);
  EXPECT_EQ(f.peak_compression, e.peak_compression);
  EXPECT_EQ(f.rebound_height, e.rebound_height);
}

TEST(EnergyLimitedStepper, ExtrapolatedPredictorSavesSqpIterationsOnTheBeams) {
  // Where two consecutive steps left a correction, the predictor adds half of their difference
  // to the last one. On the limited beams (the limits stay active for many steps and the
  // correction follows the swing) that must save SQP iterations against the last correction
  // alone (a wrong sign or weight costs iterations instead), with the same motion up to the SQP
  // tolerances.
  for (const double limit : {0.5, 0.1}) {
    BeamConfig beam;
    beam.max_energy = limit;
    beam.duration = 1.0;
    BeamConfig beam_last = beam;
    beam_last.solver.sqp_extrapolation = false;
    const BeamResult a = run_beam(beam_last), b = run_beam(beam);
    fmt::print("beam U_e <= {} J: last correction {} SQP, {} factorisations, tip deflection {:.7f} m; extrapolated {} "
               "SQP, {}, {:.7f} m\n",
               limit, a.totals.sqp_iterations, a.totals.factorizations, a.max_tip_deflection, b.totals.sqp_iterations,
               b.totals.factorizations, b.max_tip_deflection);
    EXPECT_GT(b.totals.max_active_energy, 0);
    EXPECT_EQ(b.totals.unconverged_steps, 0);
    EXPECT_LT(b.totals.sqp_iterations, a.totals.sqp_iterations * 19 / 20);
    EXPECT_LT(b.totals.factorizations, a.totals.factorizations);
    EXPECT_NEAR(b.max_tip_deflection, a.max_tip_deflection, 1e-4 * a.max_tip_deflection);
    EXPECT_LE(b.totals.max_element_energy, limit * (1.0 + beam.solver.energy_tolerance));
  }
}

}  // namespace sinew
