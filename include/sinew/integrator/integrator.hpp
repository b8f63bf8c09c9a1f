#pragma once
// One interface for every way of advancing a model over a frame: quasistatic load stepping,
// backward Euler, semi-implicit, and energy-limited stepping with constraint contact. The
// runner (run/simulation.hpp) drives any of them with one frame loop, one output module, one
// summary schema and one checkpoint format.
#include <Eigen/Core>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace sinew {

// What a step, a frame or a run did: the one stats record of every integrator. Integrator-
// specific figures (the energy-limited stepper's SQP and PGS iterations, factorisations, ...)
// are named counters.
struct StepStats {
  bool converged = true;
  int newton_iterations = 0;
  int linear_iterations = 0;  // CG iterations (1 per direct solve)
  int substeps = 0;           // completed solves or time steps
  double residual = 0.0;      // the integrator's convergence measure at the end
  double force_scale = 0.0;   // relative Newton test: the force the residual is measured against
  double energy = 0.0;        // the minimised energy (incremental potential), or the elastic energy
  double seconds = 0.0, assembly_seconds = 0.0, solve_seconds = 0.0;
  std::string failure;  // why it stopped without converging

  struct Counter {
    std::string name;
    double value = 0.0;
    bool maximum = false;  // combined by max (a worst case) instead of summed; named max_*
  };
  std::vector<Counter> counters;  // in the order first recorded
  void add_counter(const std::string& name, double value);  // summed
  void max_counter(const std::string& name, double value);  // maximum
  double counter(const std::string& name) const;            // 0 if never recorded
  // Accumulates a later part (a substep into its frame): iterations, times and counters add up,
  // residual and energy are the later part's, the first failure is kept.
  void accumulate(const StepStats& part);
};

// The state an integrator advances: positions and (dynamics) velocities, x[3 v + i] layout.
struct State {
  Eigen::VectorXd x, v;
};

// Moves the prescribed vertices (boundary conditions, then bones) to their positions at a
// (possibly fractional) frame number and flags their DOFs fixed.
using PrescribedMotion = std::function<void(double frame, Eigen::VectorXd& x, std::vector<char>& fixed)>;

// Per Newton iteration (or per step of an integrator without Newton): the iteration number and
// its residual.
using IterationProgress = std::function<void(int iteration, double residual)>;

class Integrator {
 public:
  virtual ~Integrator() = default;
  // The name summary.json and the checkpoint record: "quasistatic", "backward_euler",
  // "semi_implicit" or "energy_limited".
  virtual std::string name() const = 0;
  // Human-readable, for messages ("constrained dynamics (energy limits, paper 001)").
  virtual std::string description() const = 0;
  virtual bool dynamic() const = 0;
  // What "converged" means for this integrator's frames (summary.json "convergence_test").
  virtual std::string convergence_test() const = 0;
  // Simulated seconds per frame (0 for quasistatic runs, whose time is the frame number).
  virtual double frame_duration() const { return 0.0; }

  // Advances the state over frame `frame` (from frame - 1 to frame). On failure the state is
  // what the last attempt reached (for inspection); the runner stops there.
  virtual StepStats advance_frame(State& state, int frame, const IterationProgress& progress) = 0;

  // State of the integrator's own a checkpoint keeps (e.g. warm-start multipliers), and its
  // restoration when a run resumes after frame `frame`. Throws sinew::Error on a malformed value.
  virtual nlohmann::json checkpoint_state() const { return nlohmann::json::object(); }
  virtual void restore_state(const nlohmann::json& /*state*/, int /*frame*/) {}
};

}  // namespace sinew
