#include "sinew/scene/scene.hpp"

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <numbers>

#include "sinew/core/error.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/scene/json_reader.hpp"

namespace sinew {
namespace {

int parse_axis(JsonObject& o, const std::string& key) {
  const std::string a = o.choice(key, {"x", "y", "z"}, "z");
  return a == "x" ? 0 : (a == "y" ? 1 : 2);
}

VertexSelector parse_selector(JsonObject o) {
  const int kinds = int(o.has("box")) + int(o.has("plane")) + int(o.has("indices"));
  if (kinds != 1) o.fail("", "give exactly one of box, plane or indices");
  VertexSelector out;
  if (o.has("box")) {
    JsonObject b = o.object("box");
    BoxSelector s{b.vec3("min"), b.vec3("max")};
    if (!(s.lo.array() <= s.hi.array()).all()) b.fail("max", "must be >= min in every coordinate");
    b.finish();
    out = s;
  } else if (o.has("plane")) {
    JsonObject p = o.object("plane");
    PlaneSelector s{p.vec3("point"), p.vec3("normal")};
    if (!(s.normal.norm() > 0.0)) p.fail("normal", "must be non-zero");
    p.finish();
    out = s;
  } else {
    out = IndexSelector{o.int_list("indices", 0)};
  }
  o.finish();
  return out;
}

RigidMotion parse_motion(JsonObject o) {
  const std::string type = o.choice("type", {"pinned", "translate", "rotate", "keyframes"}, "pinned");
  RigidMotion m;
  if (type == "pinned") {
    m = Pinned{};
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
      Keyframe f;
      f.frame = key.number("frame");
      f.translation = key.vec3("translation", Eigen::Vector3d::Zero());
      if (key.has("rotation")) {
        JsonObject r = key.object("rotation");
        const Eigen::Vector3d axis = r.vec3("axis");
        if (!(axis.norm() > 0.0)) r.fail("axis", "must be non-zero");
        f.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(r.number("degrees") * std::numbers::pi / 180.0, axis.normalized()));
        r.finish();
      }
      key.finish();
      k.keys.push_back(f);
    }
    m = k;
  }
  validate_motion(m, o.file() + ": " + o.path());
  o.finish();
  return m;
}

MeshSpec parse_mesh(JsonObject o, const std::filesystem::path& folder) {
  MeshSpec spec;
  const int kinds = int(o.has("box")) + int(o.has("cylinder")) + int(o.has("sphere")) + int(o.has("voxels")) +
                    int(o.has("file"));
  if (kinds != 1) o.fail("", "give exactly one of box, cylinder, sphere, voxels or file");
  if (o.has("file")) {
    const std::filesystem::path p = o.string("file");
    spec.source = MeshFile{p.is_absolute() ? p : folder / p};
    o.finish();
    return spec;
  }
  if (o.has("box")) {
    JsonObject b = o.object("box");
    BoxShape s{b.vec3("min"), b.vec3("max")};
    if (!((s.hi - s.lo).array() > 0.0).all()) b.fail("max", "must exceed min in every coordinate");
    b.finish();
    spec.source = s;
  } else if (o.has("cylinder")) {
    JsonObject c = o.object("cylinder");
    CylinderShape s{c.vec3("center"), c.positive("radius"), c.positive("length"), parse_axis(c, "axis")};
    c.finish();
    spec.source = s;
  } else if (o.has("sphere")) {
    JsonObject c = o.object("sphere");
    spec.source = SphereShape{c.vec3("center"), c.positive("radius")};
    c.finish();
  } else {
    JsonObject v = o.object("voxels");
    VoxelShape s{v.vec3("min"), v.vec3("max"), v.ivec3("dims", 1), v.int_list("occupancy", 0)};
    if (!((s.hi - s.lo).array() > 0.0).all()) v.fail("max", "must exceed min in every coordinate");
    if (static_cast<long long>(s.occupancy.size()) != static_cast<long long>(s.dims.prod()))
      v.fail("occupancy", fmt::format("needs dims[0]*dims[1]*dims[2] = {} entries, got {}", s.dims.prod(),
                                      s.occupancy.size()));
    v.finish();
    spec.source = s;
    spec.cells = s.dims;
  }
  const int resolutions = int(o.has("cells")) + int(o.has("cell_size")) + int(o.has("resolution"));
  if (std::holds_alternative<VoxelShape>(spec.source)) {
    if (resolutions) o.fail("cells", "a voxel shape's resolution is its dims");
  } else {
    if (resolutions != 1) o.fail("cells", "give exactly one of cells, cell_size or resolution");
    if (o.has("cells")) spec.cells = o.ivec3("cells", 1);
    if (o.has("cell_size")) spec.cell_size = o.positive("cell_size");
    if (o.has("resolution")) spec.resolution = o.integer("resolution", 1);
  }
  spec.element = o.choice("element", {"hex", "tet"}, "hex") == "hex" ? ElementKind::Hex8 : ElementKind::Tet4;
  o.finish();
  return spec;
}

SolverSpec parse_solver(JsonObject o) {
  SolverSpec s;
  if (o.has("newton")) {
    JsonObject n = o.object("newton");
    s.newton.absolute_tolerance = n.positive("tolerance", s.newton.absolute_tolerance);
    s.newton.relative_tolerance = n.number("relative_tolerance", 0.0);
    if (s.newton.relative_tolerance < 0.0 || s.newton.relative_tolerance >= 1.0)
      n.fail("relative_tolerance", "must be in [0, 1)");
    s.newton.max_iterations = n.integer("max_iterations", 1, s.newton.max_iterations);
    s.newton.max_line_search_steps = n.integer("line_search_steps", 1, s.newton.max_line_search_steps);
    n.finish();
  }
  if (o.has("linear")) {
    JsonObject l = o.object("linear");
    s.linear.kind = l.choice("kind", {"cholmod", "pcg"}, "cholmod");
    s.linear.preconditioner =
        l.choice("preconditioner", {"jacobi", "block_jacobi"}, "block_jacobi") == "jacobi" ? Preconditioner::Jacobi
                                                                                            : Preconditioner::BlockJacobi3;
    s.newton.linear_tolerance = l.positive("tolerance", s.newton.linear_tolerance);
    if (s.newton.linear_tolerance >= 1.0) l.fail("tolerance", "must be below 1");
    s.newton.eisenstat_walker = l.boolean("eisenstat_walker", false);
    s.linear.max_iterations = l.integer("max_iterations", 1, s.linear.max_iterations);
    l.finish();
  }
  s.projection = parse_projection(o.choice("projection", {"clamp", "abs", "none"}, "clamp"));
  o.finish();
  return s;
}

}  // namespace

Scene parse_scene(const nlohmann::json& json, const std::filesystem::path& file) {
  const std::string name = file.string();
  JsonObject root(json, name);
  Scene scene;
  scene.file = file;
  const std::filesystem::path folder = file.parent_path();
  scene.mesh = parse_mesh(root.object("mesh"), folder);
  scene.material = material_spec_from_json(root.raw("material"), name + ": /material");
  scene.density = root.positive("density", scene.density);
  if (root.has("boundary")) {
    for (JsonObject b : root.objects("boundary")) {
      BoundarySpec spec;
      spec.name = b.string("name", b.path());
      spec.select = parse_selector(b.object("select"));
      spec.motion = b.has("motion") ? parse_motion(b.object("motion")) : RigidMotion{Pinned{}};
      b.finish();
      scene.boundary.push_back(std::move(spec));
    }
  }
  if (root.has("loads")) {
    JsonObject loads = root.object("loads");
    scene.gravity = loads.vec3("gravity", Eigen::Vector3d::Zero());
    if (loads.has("point"))
      for (JsonObject p : loads.objects("point")) {
        scene.point_loads.push_back({parse_selector(p.object("select")), p.vec3("force")});
        p.finish();
      }
    if (loads.has("traction"))
      for (JsonObject t : loads.objects("traction")) {
        scene.tractions.push_back({parse_selector(t.object("select")), t.vec3("traction")});
        t.finish();
      }
    loads.finish();
  }
  if (root.has("solver")) scene.solver = parse_solver(root.object("solver"));
  scene.frames = root.integer("frames", 1, 1);
  if (root.has("output")) {
    JsonObject o = root.object("output");
    scene.output.vtu = o.boolean("vtu", true);
    scene.output.obj = o.boolean("obj", true);
    scene.output.every = o.integer("every", 1, 1);
    o.finish();
  }
  root.finish();
  // Build the material once now so parameter problems surface at load time.
  try {
    build_material(scene.material);
  } catch (const Error& e) {
    throw e.within(name + ": /material");
  }
  return scene;
}

Scene load_scene(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw Error("cannot open scene file (missing or unreadable)", file.string());
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw Error(fmt::format("malformed JSON: {}", e.what()), file.string());
  }
  return parse_scene(json, file);
}

namespace {

Eigen::Vector3i lattice_cells(const MeshSpec& spec, const Eigen::AlignedBox3d& bounds, const std::string& where) {
  const Eigen::Vector3d size = bounds.max() - bounds.min();
  Eigen::Vector3i cells;
  if (spec.cells) return *spec.cells;
  const double h = spec.cell_size ? *spec.cell_size : size.maxCoeff() / *spec.resolution;
  for (int i = 0; i < 3; ++i) cells(i) = std::max(1, static_cast<int>(std::lround(size(i) / h)));
  if (cells.cast<double>().prod() > 5e7) throw Error("lattice would exceed 50 million cells", where);
  return cells;
}

}  // namespace

VolumeMesh build_scene_mesh(const Scene& scene) {
  const std::string where = scene.file.string() + ": /mesh";
  const MeshSpec& spec = scene.mesh;
  if (const auto* f = std::get_if<MeshFile>(&spec.source)) return read_volume_mesh(f->path);
  VolumeMesh mesh;
  if (const auto* b = std::get_if<BoxShape>(&spec.source)) {
    const Eigen::AlignedBox3d box(b->lo, b->hi);
    mesh = box_lattice(b->lo, b->hi, lattice_cells(spec, box, where));
  } else if (const auto* c = std::get_if<CylinderShape>(&spec.source)) {
    Eigen::Vector3d half = Eigen::Vector3d::Constant(c->radius);
    half(c->axis) = 0.5 * c->length;
    const Eigen::AlignedBox3d box(c->center - half, c->center + half);
    const SignedDistance sdf = cylinder_sdf(c->center, c->radius, c->length, c->axis);
    mesh = occupancy_lattice(box, lattice_cells(spec, box, where), [&](const Eigen::Vector3d& p) { return sdf(p) <= 0.0; });
  } else if (const auto* s = std::get_if<SphereShape>(&spec.source)) {
    const Eigen::Vector3d half = Eigen::Vector3d::Constant(s->radius);
    const Eigen::AlignedBox3d box(s->center - half, s->center + half);
    const SignedDistance sdf = sphere_sdf(s->center, s->radius);
    mesh = occupancy_lattice(box, lattice_cells(spec, box, where), [&](const Eigen::Vector3d& p) { return sdf(p) <= 0.0; });
  } else {
    const auto& v = std::get<VoxelShape>(spec.source);
    const Eigen::AlignedBox3d box(v.lo, v.hi);
    const Eigen::Vector3d h = (v.hi - v.lo).cwiseQuotient(v.dims.cast<double>());
    mesh = occupancy_lattice(box, v.dims, [&](const Eigen::Vector3d& p) {
      const Eigen::Vector3i ijk = ((p - v.lo).cwiseQuotient(h)).array().floor().cast<int>();
      return v.occupancy[(static_cast<size_t>(ijk(2)) * v.dims(1) + ijk(1)) * v.dims(0) + ijk(0)] != 0;
    });
  }
  if (spec.element == ElementKind::Tet4) mesh = tetrahedralize_hexes(mesh);
  mesh.validate(where);
  return mesh;
}

}  // namespace sinew
