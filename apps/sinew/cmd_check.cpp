// `sinew check SCENE.json [--state OUT_DIR] [--seed N] [--tolerance T]`: FEBio's tangent
// diagnostic. Builds the scene's energy terms, puts the body in a state of the scene (the rest
// shape moved by the first frame's boundary and bone motion, or a run's checkpoint, plus a
// small deterministic perturbation) and checks each term's gradient and Hessian against central
// differences (forms/derivative_check.hpp). Exit 0 if every term passes, 3 if one fails.
#include "cmd_check.hpp"

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>
#include <random>

#include "sinew/assembly/problem.hpp"
#include "sinew/core/error.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/forms/bone_spring_form.hpp"
#include "sinew/forms/derivative_check.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/forms/external_force_form.hpp"
#include "sinew/forms/inertia_form.hpp"
#include "sinew/forms/penalty_contact_form.hpp"
#include "sinew/forms/self_contact_form.hpp"
#include "sinew/mesh/selection.hpp"
#include "sinew/mesh/surface.hpp"
#include "sinew/model/scene.hpp"
#include "sinew/model/scene_rig.hpp"
#include "sinew/motion/prescribed_motion.hpp"
#include "sinew/forms/element_form.hpp"
#include "sinew/integrator/quasistatic_integrator.hpp"
#include "sinew/model/json_reader.hpp"
#include "sinew/model/model.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew::cli {
namespace {

struct Options {
  std::string scene, state, seed = "1", tolerance = "1e-5";
};

// OUT_DIR/checkpoint.json: the state "x" (and "v", "frame" where present).
struct SavedState {
  Eigen::VectorXd x, v;
  int frame = 0;
};

SavedState read_state(const std::filesystem::path& dir, Eigen::Index dofs) {
  const auto path = dir / "checkpoint.json";
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error("no checkpoint.json (run the scene with --out first)", path.string());
  // The scene reader's parser: bounded nesting, duplicate keys refused.
  const nlohmann::json j = read_json_file(path, "checkpoint");
  SavedState s;
  auto numbers = [&](const char* key) -> std::optional<Eigen::VectorXd> {
    if (!j.is_object() || !j.contains(key)) return std::nullopt;
    const nlohmann::json& a = j.at(key);
    const std::string where = fmt::format("{}: /{}", path.string(), key);
    if (!a.is_array()) throw Error("must be an array of numbers", where);
    if (static_cast<Eigen::Index>(a.size()) != dofs)
      throw Error(fmt::format("has {} values, the scene's mesh has {} DOFs", a.size(), dofs), where);
    Eigen::VectorXd v(dofs);
    for (Eigen::Index i = 0; i < dofs; ++i) {
      if (!a[static_cast<size_t>(i)].is_number()) throw Error("must be an array of numbers", where);
      v(i) = a[static_cast<size_t>(i)].get<double>();
    }
    if (!v.allFinite()) throw Error("state is not finite", where);
    return v;
  };
  const auto x = numbers("x");
  if (!x) throw Error("has no state \"x\" (not a checkpoint Sinew wrote)", path.string());
  s.x = *x;
  if (const auto v = numbers("v")) s.v = *v;
  if (j.contains("frame")) {
    const nlohmann::json& f = j.at("frame");
    if (!f.is_number_integer() || f.get<long long>() < 0 || f.get<long long>() > kMaxFrames)
      throw Error(fmt::format("must be a whole frame number from 0 to {}", kMaxFrames), path.string() + ": /frame");
    s.frame = static_cast<int>(f.get<long long>());
  }
  return s;
}

bool all_valid(const Problem& p, const Eigen::VectorXd& x) {
  for (const auto& f : p.forms())
    if (!f->is_valid(x)) return false;
  return true;
}

// Largest relative error of the exact element gradients dU_e/dx against central differences of
// U_e, over up to 32 elements spread through the mesh.
double element_gradient_error(const ElementForm& form, const Eigen::VectorXd& x, double size) {
  const Discretization& d = form.discretization();
  const auto& elements = d.mesh().elements;
  const Eigen::Index n = d.num_elements(), stride = std::max<Eigen::Index>(1, n / 32);
  const double h = 1e-6 * size;
  double worst = 0.0;
  for (Eigen::Index e = 0; e < n; e += stride) {
    const Eigen::VectorXd g = form.element_gradient(e, x, JacobianKind::Exact);
    Eigen::VectorXd fd(g.size());
    Eigen::VectorXd y = x;
    for (Eigen::Index k = 0; k < g.size(); ++k) {
      const Eigen::Index dof = 3 * elements(e, k / 3) + k % 3;
      y(dof) = x(dof) + h;
      const double up = form.element_value(e, y);
      y(dof) = x(dof) - h;
      fd(k) = (up - form.element_value(e, y)) / (2 * h);
      y(dof) = x(dof);
    }
    worst = std::max(worst, (g - fd).norm() / std::max(g.norm(), 1e-300));
  }
  return worst;
}

std::string number(double v) { return std::isfinite(v) ? fmt::format("{:.1e}", v) : std::string("nan"); }

void check(const Options& o, int& exit_code) {
  const long seed = parse_integer(o.seed, "--seed");
  if (seed < 0 || seed > 4294967295L) throw Error(fmt::format("must be between 0 and 4294967295, got {}", seed), "--seed");
  const double tolerance = parse_number(o.tolerance, "--tolerance");
  if (!(tolerance > 0.0)) throw Error(fmt::format("must be positive, got {}", tolerance), "--tolerance");

  const Scene scene = load_scene(o.scene);
  Model model = build_model(scene);  // the model `sinew run` builds
  const Discretization& disc = *model.disc;
  const VolumeMesh& mesh = disc.mesh();
  Problem& problem = *model.problem;

  // The state: x_n where the step starts (lagged data: friction, inertia, damping) and x, the
  // step's end with the boundary moved, where the derivatives are checked.
  Eigen::VectorXd x_n = mesh.rest_positions();
  Eigen::VectorXd v = model.initial.v;
  double frame0 = 0.0, frame1 = 1.0;
  std::string where;
  if (!o.state.empty()) {
    SavedState s = read_state(o.state, x_n.size());
    x_n = s.x;
    if (s.v.size() == x_n.size()) v = s.v;
    frame0 = frame1 = s.frame;
    where = fmt::format("checkpoint of frame {} ({})", s.frame, (std::filesystem::path(o.state) / "checkpoint.json").string());
  }
  Eigen::VectorXd x = x_n;
  if (o.state.empty()) {
    // The first frame's boundary and bone motion applied to the rest shape; halved while an
    // element would leave its material's domain (only the constrained vertices move).
    double fraction = 1.0;
    for (int split = 0; split <= kMaxMotionSplits; ++split, fraction *= 0.5) {
      x = x_n;
      std::vector<char> fixed(x.size(), 0);
      apply_kinematics(*model.kinematics, mesh.vertices, fraction, x, fixed);
      model.rig.apply(fraction, mesh.vertices, x, fixed);
      if (all_valid(problem, x)) break;
    }
    if (!all_valid(problem, x)) throw Error("the first frame's boundary motion leaves the material's domain even when split", o.scene);
    frame1 = fraction;
    where = fraction == 1.0 ? std::string("rest shape with frame 1's boundary motion")
                            : fmt::format("rest shape with {:g} of frame 1's boundary motion (more inverts elements)", fraction);
  }
  // A perturbation of 1% of the mean element size, from --seed; kept only where valid.
  double volume = 0.0;
  for (Eigen::Index e = 0; e < disc.num_elements(); ++e) volume += disc.rest_volume(e);
  const double size = std::cbrt(volume / std::max<Eigen::Index>(1, disc.num_elements()));
  std::mt19937 rng(static_cast<unsigned>(seed));
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd noise(x.size());
  for (Eigen::Index i = 0; i < noise.size(); ++i) noise(i) = u(rng);
  double amplitude = 1e-2 * size;
  while (amplitude > 1e-6 * size && !all_valid(problem, x + amplitude * noise)) amplitude *= 0.5;
  x += amplitude * noise;

  // Lagged data of the step x_n -> x.
  for (const auto& form : problem.forms()) {
    if (auto inertia = std::dynamic_pointer_cast<InertiaForm>(form)) inertia->set_prediction(x_n, v.size() ? v : Eigen::VectorXd::Zero(x_n.size()));
    if (auto damping = std::dynamic_pointer_cast<DampingForm>(form)) damping->begin_step(x_n);
  }
  if (model.contact) {
    const double slip = scene.dynamics ? scene.dynamics->friction_velocity * scene.dynamics->time_step / scene.dynamics->substeps : 0.0;
    model.contact->begin_step(x_n, frame0, frame1, slip);
  }
  if (model.rig.springs) model.rig.springs->set_frame(frame1);
  if (model.rig.contact) model.rig.contact->refresh(x);

  FormCheckOptions options;
  options.tolerance = tolerance;
  options.seed = static_cast<unsigned>(seed);
  fmt::print("{}: {} vertices, {} elements\n", o.scene, mesh.num_vertices(), mesh.num_elements());
  fmt::print("state: {}, perturbed by {:.2g} (seed {})\n", where, amplitude, seed);
  if (scene.constraints && !scene.obstacles.empty())
    fmt::print("note: obstacles meet the body by constraint contact here (no energy term to check)\n");
  fmt::print("{:<14} {:>8} {:>12} {:>9} {:>9} {:>9} {:>9} {:>10}  {}\n", "form", "DOFs", "directions", "step",
             "gradient", "Hessian", "asymmetry", "min eig", fmt::format("result (tolerance {:g})", tolerance));
  bool all_pass = true;
  for (const auto& form : problem.forms()) {
    if (!form->exact_derivatives()) {
      // A deliberate approximation (the corotational warped force and stiffness): check what is
      // exact, the element energies' gradients, on a sample of elements.
      const auto element_form = std::dynamic_pointer_cast<const ElementForm>(form);
      if (!element_form) {
        // A follower pressure on an open surface: not conservative, so no energy to check against.
        fmt::print("{:<14} {:>8} {:>12} {:>9} {:>9} {:>9} {:>9} {:>10}  {}\n", form->name(), x.size(), "-", "-", "-", "-",
                   "-", "-", "not checked");
        fmt::print("note: {}: its force has no potential here (a pressure on an open surface; docs/scene-format.md#loads)\n",
                   form->name());
        continue;
      }
      const double error = element_gradient_error(*element_form, x, size);
      const bool ok = error <= tolerance;
      all_pass = all_pass && ok;
      fmt::print("{:<14} {:>8} {:>12} {:>9} {:>9} {:>9} {:>9} {:>10}  {}\n", form->name(), x.size(), "elements",
                 number(1e-6 * size), number(error), "-", "-", "-",
                 ok ? "pass" : "FAIL");
      fmt::print("note: {}: its force and stiffness are warped by design (rotation held fixed); the row checks its exact "
                 "element gradients\n",
                 form->name());
      continue;
    }
    const FormCheck c = check_form(*form, x, options);
    all_pass = all_pass && c.passed();
    fmt::print("{:<14} {:>8} {:>12} {:>9} {:>9} {:>9} {:>9} {:>10}  {}\n", c.form, c.dofs,
               c.coordinate ? fmt::format("{} (all)", c.directions) : fmt::format("{} random", c.directions),
               number(c.step), number(c.gradient_error), number(c.hessian_error), number(c.asymmetry),
               c.projected ? number(c.min_eigenvalue) : std::string("-"), c.passed() ? "pass" : "FAIL");
  }
  fmt::print("errors are relative (docs/scene-format.md#checking-derivatives); min eig: smallest eigenvalue of a PSD-projected Hessian over its norm\n");
  if (!all_pass) {
    fmt::print(stderr, "sinew: a term's derivatives do not match its finite differences (tolerance {:g})\n", tolerance);
    exit_code = 3;
  }
}

}  // namespace

Command add_check_command(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("check", "Check each energy term's gradient and Hessian on a scene (finite differences)");
  cmd->add_option("scene", opts->scene, "scene file")->required();
  cmd->add_option("--state", opts->state, "check at the state of a run's checkpoint (OUT_DIR/checkpoint.json)");
  cmd->add_option("--seed", opts->seed, "seed of the perturbation and the random directions (default 1)");
  cmd->add_option("--tolerance", opts->tolerance, "largest relative error that passes (default 1e-5)");
  return {cmd, [opts, &exit_code] { check(*opts, exit_code); }};
}

}  // namespace sinew::cli
