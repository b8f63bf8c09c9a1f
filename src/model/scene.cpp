#include "sinew/model/scene.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <set>

#include "sinew/core/error.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/model/json_reader.hpp"
#include "sinew/model/scene_surface.hpp"
#include "scene_sections.hpp"
#include "sinew/model/scene_rig.hpp"
#include "sinew/motion/rig.hpp"
#include "sinew/element/mesh_validation.hpp"
#include "sinew/solver/preconditioner.hpp"

namespace sinew {
namespace {

int parse_axis(JsonObject& o, const std::string& key) {
  const std::string a = o.choice(key, {"x", "y", "z"}, "z");
  return a == "x" ? 0 : (a == "y" ? 1 : 2);
}

VertexSelector parse_selector(JsonObject o) {
  o.allow({"box", "plane", "indices", "group", "dimension"});
  const int kinds = int(o.has("box")) + int(o.has("plane")) + int(o.has("indices")) + int(o.has("group"));
  if (kinds != 1) o.fail("", "give exactly one of box, plane, indices or group");
  if (o.has("dimension") && !o.has("group")) o.fail("dimension", "only with group");
  VertexSelector out;
  if (o.has("group")) {
    // A mesh file's group (Gmsh physical group) by name or tag; checked against the mesh when
    // the model is built.
    GroupSelector g;
    const nlohmann::json& group = o.raw("group");
    if (!group.is_string() && !group.is_number()) o.fail("group", "must be a group's name (a string) or tag (an integer)");
    if (group.is_string()) {
      g.name = o.string("group");
      if (g.name->empty()) o.fail("group", "must not be empty");
    } else {
      g.tag = o.integer("group", std::numeric_limits<int>::min());
    }
    if (o.has("dimension")) g.dimension = o.integer("dimension", 0);
    if (g.dimension && *g.dimension > 3) o.fail("dimension", "must be 0, 1, 2 or 3");
    out = g;
  } else if (o.has("box")) {
    JsonObject b = o.object("box");
    b.allow({"min", "max"});
    BoxSelector s{b.vec3("min"), b.vec3("max")};
    if (!(s.lo.array() <= s.hi.array()).all()) b.fail("max", "must be >= min in every coordinate");
    b.finish();
    out = s;
  } else if (o.has("plane")) {
    JsonObject p = o.object("plane");
    p.allow({"point", "normal"});
    PlaneSelector s{p.vec3("point"), p.vec3("normal")};
    if (!(s.normal.norm() > 0.0)) p.fail("normal", "must be non-zero");
    p.finish();
    out = s;
  } else {
    out = IndexSelector{o.int_list("indices", 0)};
    if (std::get<IndexSelector>(out).indices.empty()) o.fail("indices", "must not be empty");
  }
  o.finish();
  return out;
}

}  // namespace

RigidMotion parse_motion(JsonObject o) {
  o.allow({"type", "per_frame", "center", "axis", "degrees_per_frame", "keys", "displacement", "amplitude"});
  const std::string type = o.choice("type", {"pinned", "translate", "rotate", "keyframes", "displace"}, "pinned");
  RigidMotion m;
  if (type == "pinned") {
    m = Pinned{};
  } else if (type == "displace") {
    Displacement d;
    d.value = o.vec3("displacement");
    d.amplitude = o.has("amplitude") ? parse_amplitude(o, "amplitude") : Amplitude{{}, true};
    m = d;
  } else if (type == "translate") {
    m = Translation{o.vec3("per_frame")};
  } else if (type == "rotate") {
    Rotation r;
    r.center = o.vec3("center");
    r.axis = o.vec3("axis");
    if (!(r.axis.norm() > 0.0)) o.fail("axis", "must be non-zero");
    r.angle_per_frame = o.number("degrees_per_frame") * std::numbers::pi / 180.0;
    m = r;
  } else {
    Keyframes k;
    for (JsonObject key : o.objects("keys")) {
      key.allow({"frame", "translation", "rotation"});
      Keyframe f;
      f.frame = key.number("frame");
      if (!k.keys.empty() && !(f.frame > k.keys.back().frame))
        key.fail("frame", fmt::format("must be after the previous keyframe's ({} <= {})", f.frame, k.keys.back().frame));
      f.translation = key.vec3("translation", Eigen::Vector3d::Zero());
      if (key.has("rotation")) {
        JsonObject r = key.object("rotation");
        r.allow({"axis", "degrees"});
        const Eigen::Vector3d axis = r.vec3("axis");
        if (!(axis.norm() > 0.0)) r.fail("axis", "must be non-zero");
        f.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(r.number("degrees") * std::numbers::pi / 180.0, axis.normalized()));
        r.finish();
      }
      key.finish();
      k.keys.push_back(f);
    }
    if (k.keys.empty()) o.fail("keys", "needs at least one keyframe");
    m = k;
  }
  validate_motion(m, o.file() + ": " + o.path());
  o.finish();
  return m;
}

namespace {

MeshSpec parse_mesh(JsonObject o, const std::filesystem::path& folder) {
  o.allow({"box", "cylinder", "sphere", "voxels", "file", "cells", "cell_size", "resolution", "element", "surface",
           "tetrahedralize", "max_edge", "non_manifold", "embed", "reorient", "grid_origin"});
  MeshSpec spec;
  if (parse_surface_mesh(o, folder, spec)) return spec;  // scene_surface.cpp
  if (o.has("grid_origin")) o.fail("grid_origin", "only with surface (a voxelised surface)");
  spec.embed = parse_embedded_surface(o, folder, std::nullopt);
  const int kinds = int(o.has("box")) + int(o.has("cylinder")) + int(o.has("sphere")) + int(o.has("voxels")) +
                    int(o.has("file"));
  if (kinds != 1) o.fail("", "give exactly one of box, cylinder, sphere, voxels or file");
  if (o.has("file")) {
    const std::filesystem::path p = o.string("file");
    if (p.empty()) o.fail("file", "must name a mesh file");
    const std::filesystem::path resolved = p.is_absolute() ? p : folder / p;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(resolved, ec))
      o.fail("file", fmt::format("mesh file not found: {}{}", resolved.string(),
                                 p.is_absolute() ? "" : " (relative paths start at the scene file's folder)"));
    spec.source = MeshFile{resolved, o.boolean("reorient", false)};
    for (const char* key : {"cells", "cell_size", "resolution"})
      if (o.has(key)) o.fail(key, "a mesh file has its own resolution");
    if (o.has("element")) o.fail("element", "a mesh file's element kind comes from the file");
    o.finish();
    return spec;
  }
  if (o.has("box")) {
    JsonObject b = o.object("box");
    b.allow({"min", "max"});
    BoxShape s{b.vec3("min"), b.vec3("max")};
    if (!((s.hi - s.lo).array() > 0.0).all()) b.fail("max", "must exceed min in every coordinate");
    b.finish();
    spec.source = s;
  } else if (o.has("cylinder")) {
    JsonObject c = o.object("cylinder");
    c.allow({"center", "radius", "length", "axis"});
    CylinderShape s{c.vec3("center"), c.positive("radius"), c.positive("length"), parse_axis(c, "axis")};
    c.finish();
    spec.source = s;
  } else if (o.has("sphere")) {
    JsonObject c = o.object("sphere");
    c.allow({"center", "radius"});
    spec.source = SphereShape{c.vec3("center"), c.positive("radius")};
    c.finish();
  } else {
    JsonObject v = o.object("voxels");
    v.allow({"min", "max", "dims", "occupancy"});
    VoxelShape s{v.vec3("min"), v.vec3("max"), v.ivec3("dims", 1), v.int_list("occupancy", 0)};
    if (!((s.hi - s.lo).array() > 0.0).all()) v.fail("max", "must exceed min in every coordinate");
    try {
      check_lattice_cells(s.dims, "");  // 64-bit product, so dims that wrap an int cannot pass
    } catch (const Error& e) {
      v.fail("dims", e.message());
    }
    const std::int64_t entries = std::int64_t{s.dims(0)} * s.dims(1) * s.dims(2);
    if (static_cast<std::int64_t>(s.occupancy.size()) != entries)
      v.fail("occupancy", fmt::format("needs dims[0]*dims[1]*dims[2] = {} entries, got {}", entries,
                                      s.occupancy.size()));
    if (std::none_of(s.occupancy.begin(), s.occupancy.end(), [](int c) { return c != 0; }))
      v.fail("occupancy", "no voxel is occupied");
    v.finish();
    spec.source = s;
    spec.cells = s.dims;
  }
  const int resolutions = int(o.has("cells")) + int(o.has("cell_size")) + int(o.has("resolution"));
  if (std::holds_alternative<VoxelShape>(spec.source)) {
    if (resolutions) o.fail("cells", "a voxel shape's resolution is its dims");
  } else {
    if (resolutions != 1) o.fail("", "give exactly one of cells, cell_size or resolution");
    if (o.has("cells")) {
      spec.cells = o.ivec3("cells", 1);
      try {
        check_lattice_cells(*spec.cells, "");
      } catch (const Error& e) {
        o.fail("cells", e.message());
      }
    }
    if (o.has("cell_size")) spec.cell_size = o.positive("cell_size");
    if (o.has("resolution")) spec.resolution = o.integer("resolution", 1);
  }
  spec.element = o.choice("element", {"hex", "tet"}, "hex") == "hex" ? ElementKind::Hex8 : ElementKind::Tet4;
  o.finish();
  return spec;
}

SolverSpec parse_solver(JsonObject o) {
  o.allow({"newton", "linear", "projection", "predictor"});
  SolverSpec s;
  if (o.has("newton")) {
    JsonObject n = o.object("newton");
    n.allow({"convergence", "residual_tolerance", "step_tolerance", "tolerance", "relative_tolerance",
             "max_iterations", "line_search_steps"});
    const std::string test = n.choice("convergence", {"relative", "absolute"}, "relative");
    if (test == "relative") {
      // A force tolerance means nothing to the dimensionless test: refuse it rather than
      // silently reinterpret an older scene's "tolerance" as a ratio.
      for (const char* key : {"tolerance", "relative_tolerance"})
        if (n.has(key))
          n.fail(key, "is a setting of the absolute test: add \"convergence\": \"absolute\" (the default relative "
                      "test takes residual_tolerance and step_tolerance)");
      s.newton.test = ConvergenceTest::Relative;
      s.newton.residual_tolerance = n.positive("residual_tolerance", s.newton.residual_tolerance);
      if (s.newton.residual_tolerance >= 1.0) n.fail("residual_tolerance", "must be below 1 (a fraction of the force scale)");
      if (s.newton.residual_tolerance < 1e-14)
        n.fail("residual_tolerance", "must be at least 1e-14: double precision cannot resolve a smaller fraction");
      s.newton.step_tolerance = n.positive("step_tolerance", s.newton.step_tolerance);
      if (s.newton.step_tolerance >= 1.0) n.fail("step_tolerance", "must be below 1 (a fraction of the displacement)");
    } else {
      for (const char* key : {"residual_tolerance", "step_tolerance"})
        if (n.has(key)) n.fail(key, "is a setting of the relative test; the absolute test takes tolerance (a force)");
      s.newton.test = ConvergenceTest::Absolute;
      s.newton.absolute_tolerance = n.positive("tolerance", s.newton.absolute_tolerance);
      s.newton.relative_tolerance = n.number("relative_tolerance", 0.0);
      if (s.newton.relative_tolerance < 0.0 || s.newton.relative_tolerance >= 1.0)
        n.fail("relative_tolerance", "must be in [0, 1)");
    }
    s.newton.max_iterations = n.integer("max_iterations", 1, s.newton.max_iterations);
    s.newton.max_line_search_steps = n.integer("line_search_steps", 1, s.newton.max_line_search_steps);
    n.finish();
  }
  if (o.has("linear")) {
    JsonObject l = o.object("linear");
    l.allow({"kind", "preconditioner", "tolerance", "eisenstat_walker", "max_iterations", "hessian"});
    s.linear.kind = l.choice("kind", {"cholmod", "pcg"}, "cholmod");
    // Any registered preconditioner (solver/preconditioner.hpp); an unknown name is rejected
    // with the registered ones listed.
    s.linear.preconditioner = l.choice("preconditioner", registered_preconditioners(), s.linear.preconditioner);
    s.newton.linear_tolerance = l.positive("tolerance", s.newton.linear_tolerance);
    if (s.newton.linear_tolerance >= 1.0) l.fail("tolerance", "must be below 1");
    s.newton.eisenstat_walker = l.boolean("eisenstat_walker", false);
    s.linear.max_iterations = l.integer("max_iterations", 1, s.linear.max_iterations);
    s.linear.matrix_free = l.choice("hessian", {"assembled", "matrix_free"}, "assembled") == "matrix_free";
    if (s.linear.matrix_free && s.linear.kind != "pcg")
      l.fail("hessian", "matrix_free needs \"kind\": \"pcg\" (a direct solver factorises the assembled matrix)");
    if (s.linear.matrix_free && s.linear.preconditioner != "jacobi" && s.linear.preconditioner != "block_jacobi" &&
        s.linear.preconditioner != "multigrid")
      l.fail("hessian", fmt::format("matrix_free works with the jacobi, block_jacobi or multigrid preconditioner, not {} "
                                    "(it needs the assembled matrix)",
                                    s.linear.preconditioner));
    l.finish();
  }
  const std::string projection = o.choice("projection", {"adaptive", "clamp", "abs", "none"}, "adaptive");
  // "adaptive": the clamped Hessian far from equilibrium, the true one near it (NewtonSettings::exact_tail).
  s.projection = parse_projection(projection == "adaptive" ? "clamp" : projection);
  s.newton.exact_tail = projection == "adaptive";
  const std::string predictor = o.choice("predictor", {"auto", "extrapolate", "tangent", "none"}, "auto");
  s.predictor = predictor == "extrapolate" ? LoadStepPredictor::Extrapolate
                : predictor == "tangent"   ? LoadStepPredictor::Tangent
                : predictor == "none"      ? LoadStepPredictor::None
                                           : LoadStepPredictor::Auto;
  o.finish();
  return s;
}

// The material reader joins keys with '.' ("nu", "mix.alpha_mu"); scene errors use JSON
// pointers, so "/material/mix/alpha_mu".

}  // namespace

Scene parse_scene(const nlohmann::json& json, const std::filesystem::path& file) {
  const std::string name = file.string();
  JsonObject root(json, name);
  root.allow({"description", "mesh", "material", "density", "boundary", "loads", "solver", "frames", "output",
              "constraints", "dynamics", "obstacles", "rig", "self_contact"});
  Scene scene;
  scene.file = file;
  scene.description = root.string("description", "");
  const std::filesystem::path folder = file.parent_path();
  scene.mesh = parse_mesh(root.object("mesh"), folder);
  const nlohmann::json& material = root.raw("material");
  scene.material = material_spec_from_json(material, name + ": /material");
  scene.density = root.positive("density", scene.density);
  if (root.has("boundary"))
    for (JsonObject b : root.objects("boundary")) scene.boundary.push_back(parse_boundary_condition(b, parse_selector));
  if (root.has("loads")) {
    JsonObject loads = root.object("loads");
    loads.allow({"gravity", "point", "traction", "pressure", "body_force"});
    if (loads.has("gravity") && loads.raw("gravity").is_object()) {
      JsonObject g = loads.object("gravity");
      g.allow({"acceleration", "amplitude"});
      scene.gravity = g.vec3("acceleration");
      if (g.has("amplitude")) scene.gravity_amplitude = parse_amplitude(g, "amplitude");
      g.finish();
    } else {
      scene.gravity = loads.vec3("gravity", Eigen::Vector3d::Zero());
    }
    if (loads.has("point"))
      for (JsonObject p : loads.objects("point")) {
        p.allow({"select", "force", "amplitude"});
        scene.point_loads.push_back({parse_selector(p.object("select")), p.vec3("force"),
                                     p.has("amplitude") ? parse_amplitude(p, "amplitude") : Amplitude{}});
        p.finish();
      }
    if (loads.has("traction"))
      for (JsonObject t : loads.objects("traction")) {
        t.allow({"select", "traction", "amplitude"});
        scene.tractions.push_back({parse_selector(t.object("select")), t.vec3("traction"),
                                   t.has("amplitude") ? parse_amplitude(t, "amplitude") : Amplitude{}});
        t.finish();
      }
    if (loads.has("pressure"))
      for (JsonObject p : loads.objects("pressure")) {
        p.allow({"select", "pressure", "amplitude"});
        scene.pressures.push_back({parse_selector(p.object("select")), p.number("pressure"),
                                   p.has("amplitude") ? parse_amplitude(p, "amplitude") : Amplitude{}});
        p.finish();
      }
    if (loads.has("body_force") && loads.raw("body_force").is_object()) {  // as gravity
      JsonObject b = loads.object("body_force");
      b.allow({"force", "amplitude"});
      scene.body_force = b.vec3("force");
      if (b.has("amplitude")) scene.body_force_amplitude = parse_amplitude(b, "amplitude");
      b.finish();
    } else {
      scene.body_force = loads.vec3("body_force", Eigen::Vector3d::Zero());
    }
    loads.finish();
  }
  if (root.has("solver")) scene.solver = parse_solver(root.object("solver"));
  if (root.has("constraints")) scene.constraints = parse_constraints(root.object("constraints"));
  scene.frames = root.integer("frames", 1, 1);
  if (scene.frames > kMaxFrames) root.fail("frames", fmt::format("must be at most {}, got {}", kMaxFrames, scene.frames));
  if (root.has("output")) {
    JsonObject o = root.object("output");
    o.allow({"vtu", "obj", "every", "selections"});
    scene.output.vtu = o.boolean("vtu", true);
    scene.output.obj = o.boolean("obj", true);
    scene.output.every = o.integer("every", 1, 1);
    scene.output.selections = o.boolean("selections", false);
    o.finish();
  }
  parse_dynamics_sections(root, scene);  // scene_dynamics.cpp
  if (scene.dynamics && json.contains("solver") && json.at("solver").contains("predictor"))  // an object: parse_solver checked
    throw Error("applies to quasistatic runs only (this scene has dynamics: each time step starts from the last)",
                name + ": /solver/predictor");
  if (scene.constraints && scene.solver.linear.matrix_free)
    throw Error("matrix_free is not available with constraints (the energy-limited stepper factorises its matrices)",
                name + ": /solver/linear/hessian");
  parse_scene_rig(root, scene);
  root.finish();
  resolve_ramps(scene);
  // Build the material once now so parameter problems surface at load time.
  try {
    build_material(scene.material);
  } catch (const Error& e) {
    throw e.within(name + ": /material");  // its context names the family and parameter
  }
  // Only now: a value that passed every check has the scene's bounded depth (dumping a hostile,
  // deeply nested one would recurse past the stack).
  scene.text = json.dump();
  return scene;
}

std::vector<std::filesystem::path> scene_input_files(const Scene& scene) {
  std::vector<std::filesystem::path> files;
  if (const auto* f = std::get_if<MeshFile>(&scene.mesh.source)) files.push_back(f->path);
  if (const auto* f = std::get_if<SurfaceVoxels>(&scene.mesh.source)) files.push_back(f->path);
  if (const auto* f = std::get_if<SurfaceTetrahedra>(&scene.mesh.source)) files.push_back(f->path);
  if (scene.mesh.embed) files.push_back(*scene.mesh.embed);
  if (scene.rig) files.insert(files.end(), scene.rig->files.begin(), scene.rig->files.end());
  std::vector<std::filesystem::path> unique;
  for (const auto& f : files)
    if (std::find(unique.begin(), unique.end(), f) == unique.end()) unique.push_back(f);
  return unique;
}

RigidMotion motion_from_json(const nlohmann::json& json, const std::string& context) {
  return parse_motion(JsonObject(json, context));
}

Scene load_scene(const std::filesystem::path& file) {
  const nlohmann::json json = read_json_file(file, "scene");
  return parse_scene(json, file);
}

namespace {

Eigen::Vector3i lattice_cells(const MeshSpec& spec, const Eigen::AlignedBox3d& bounds, const std::string& where) {
  const Eigen::Vector3d size = bounds.max() - bounds.min();
  if (spec.cells) return *spec.cells;
  const double h = spec.cell_size ? *spec.cell_size : size.maxCoeff() / *spec.resolution;
  return lattice_cell_counts(size, h, /*ceil=*/false, where + (spec.cell_size ? "/cell_size" : "/resolution"));
}


// The hexahedral lattice of a generated shape.
VolumeMesh shape_lattice(const MeshSpec& spec, const std::string& where) {
  if (const auto* b = std::get_if<BoxShape>(&spec.source)) {
    const Eigen::AlignedBox3d box(b->lo, b->hi);
    return box_lattice(b->lo, b->hi, lattice_cells(spec, box, where));
  }
  if (const auto* c = std::get_if<CylinderShape>(&spec.source)) {
    Eigen::Vector3d half = Eigen::Vector3d::Constant(c->radius);
    half(c->axis) = 0.5 * c->length;
    const Eigen::AlignedBox3d box(c->center - half, c->center + half);
    const SignedDistance sdf = cylinder_sdf(c->center, c->radius, c->length, c->axis);
    return occupancy_lattice(box, lattice_cells(spec, box, where), [&](const Eigen::Vector3d& p) { return sdf(p) <= 0.0; });
  }
  if (const auto* s = std::get_if<SphereShape>(&spec.source)) {
    const Eigen::Vector3d half = Eigen::Vector3d::Constant(s->radius);
    const Eigen::AlignedBox3d box(s->center - half, s->center + half);
    const SignedDistance sdf = sphere_sdf(s->center, s->radius);
    return occupancy_lattice(box, lattice_cells(spec, box, where), [&](const Eigen::Vector3d& p) { return sdf(p) <= 0.0; });
  }
  const auto& v = std::get<VoxelShape>(spec.source);
  const Eigen::AlignedBox3d box(v.lo, v.hi);
  const Eigen::Vector3d h = (v.hi - v.lo).cwiseQuotient(v.dims.cast<double>());
  return occupancy_lattice(box, v.dims, [&](const Eigen::Vector3d& p) {
    // p is a cell centre; clamp guards the rounding of (p - lo) / h at the last cell.
    const Eigen::Vector3i ijk = ((p - v.lo).cwiseQuotient(h)).array().floor().cast<int>().max(0).min(v.dims.array() - 1);
    return v.occupancy[(static_cast<size_t>(ijk(2)) * v.dims(1) + ijk(1)) * v.dims(0) + ijk(0)] != 0;
  });
}

}  // namespace

VolumeMesh build_scene_mesh(const Scene& scene) {
  const std::string where = scene.file.string() + ": /mesh";
  const MeshSpec& spec = scene.mesh;
  if (const auto* f = std::get_if<MeshFile>(&spec.source)) {
    try {
      return read_volume_mesh(f->path, {f->reorient});  // validated by the reader
    } catch (const Error& e) {
      throw e.within(where + "/file");
    }
  }
  VolumeMesh mesh;
  try {
    if (auto surface_mesh = build_surface_mesh(spec)) {  // scene_surface.cpp
      validate_mesh(*surface_mesh, where);
      return *surface_mesh;
    }
    mesh = shape_lattice(spec, where);
    if (spec.element == ElementKind::Tet4) mesh = tetrahedralize_hexes(mesh);
  } catch (const Error& e) {
    throw e.context().rfind(where, 0) == 0 ? e : e.within(where);
  }
  validate_mesh(mesh, where);
  return mesh;
}

}  // namespace sinew
