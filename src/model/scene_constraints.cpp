#include "sinew/model/scene_constraints.hpp"

#include <fmt/format.h>

#include "sinew/model/json_reader.hpp"

namespace sinew {

ConstraintsSpec parse_constraints(JsonObject o) {
  // One way to say each thing: time stepping lives in `dynamics`, contact geometry in `obstacles`.
  const std::pair<const char*, const char*> moved[] = {{"time_step", "dynamics.time_step (seconds per frame)"},
                                                       {"steps_per_frame", "dynamics.substeps"},
                                                       {"initial_velocity", "dynamics.initial_velocity"}};
  for (const auto& [key, where] : moved)
    if (o.has(key)) o.fail(key, fmt::format("not a constraints setting: use {}", where));
  o.allow({"model", "energy_limit", "contact", "pgs", "sqp", "factorization"});
  ConstraintsSpec spec;
  spec.model = o.choice("model", {"corotational", "material"}, "corotational");
  if (o.has("energy_limit")) {
    JsonObject e = o.object("energy_limit");
    e.allow({"max_energy", "jacobian", "activation", "tolerance"});
    EnergyLimit limit;
    limit.max_energy = e.positive("max_energy");
    limit.jacobian = parse_jacobian_kind(e.choice("jacobian", {"exact", "warped"}, "exact"));
    if (limit.jacobian == JacobianKind::Warped && spec.model != "corotational")
      e.fail("jacobian", "the warped-force Jacobian exists only for the corotational model");
    spec.step.activation = e.number("activation", spec.step.activation);
    if (!(spec.step.activation >= 0.0 && spec.step.activation <= 1.0))
      e.fail("activation", fmt::format("must be in [0, 1], got {}", spec.step.activation));
    spec.step.energy_tolerance = e.positive("tolerance", spec.step.energy_tolerance);
    e.finish();
    spec.step.energy_limit = limit;
  }
  if (o.has("contact")) {
    JsonObject c = o.object("contact");
    if (c.has("ground")) c.fail("ground", "contact geometry lives in `obstacles`: use an obstacle of type \"plane\"");
    if (c.has("friction")) c.fail("friction", "friction is per obstacle: use the obstacle's `friction`");
    c.allow({"margin", "tolerance"});
    spec.contact_margin = c.number("margin", spec.contact_margin);
    if (!(spec.contact_margin >= 0.0)) c.fail("margin", fmt::format("must be non-negative, got {}", spec.contact_margin));
    spec.step.contact_tolerance = c.positive("tolerance", spec.step.contact_tolerance);
    c.finish();
  }
  if (o.has("pgs")) {
    JsonObject p = o.object("pgs");
    p.allow({"iterations", "tolerance"});
    spec.step.pgs.max_iterations = p.integer("iterations", 1, spec.step.pgs.max_iterations);
    spec.step.pgs.tolerance = p.positive("tolerance", spec.step.pgs.tolerance);
    p.finish();
  }
  if (o.has("sqp")) {
    JsonObject s = o.object("sqp");
    s.allow({"iterations"});
    spec.step.sqp_max_iterations = s.integer("iterations", 1, spec.step.sqp_max_iterations);
    s.finish();
  }
  if (o.has("factorization")) {
    JsonObject f = o.object("factorization");
    f.allow({"reuse", "max_cg_iterations", "cg_tolerance", "column_reuse_tolerance"});
    FactorizationReuse& r = spec.step.reuse;
    r.enabled = f.boolean("reuse", r.enabled);
    r.max_cg_iterations = f.integer("max_cg_iterations", 1, r.max_cg_iterations);
    r.cg_tolerance = f.positive("cg_tolerance", r.cg_tolerance);
    if (!(r.cg_tolerance < 1.0)) f.fail("cg_tolerance", fmt::format("must be below 1, got {}", r.cg_tolerance));
    r.column_reuse_tolerance = f.number("column_reuse_tolerance", r.column_reuse_tolerance);
    if (!(r.column_reuse_tolerance >= 0.0 && r.column_reuse_tolerance < 1.0))
      f.fail("column_reuse_tolerance", fmt::format("must be in [0, 1), got {}", r.column_reuse_tolerance));
    f.finish();
  }
  o.finish();
  return spec;
}

}  // namespace sinew
