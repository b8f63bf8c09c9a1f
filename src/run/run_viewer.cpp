#include "sinew/run/run_viewer.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>

#include "sinew/motion/obstacle.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/io/surface_reader.hpp"
#include "sinew/material/spec.hpp"
#include "sinew/element/nodal_fields.hpp"
#include "sinew/motion/bone_surface.hpp"
#include "sinew/motion/rig.hpp"

namespace sinew {
namespace {

const std::vector<std::string> kFieldNames = {"J", "von_mises"};

Mat3 cauchy_stress(const Material& material, const Mat3& F) {
  const double J = F.determinant();
  return material.pk1(F) * F.transpose() / J;
}

}  // namespace

ElementStressFields element_stress_fields(const Discretization& disc, const Material& material, const Eigen::VectorXd& x) {
  ElementStressFields f;
  const Eigen::Index m = disc.num_elements();
  f.J.resize(m);
  f.von_mises.resize(m);
  for (Eigen::Index e = 0; e < m; ++e) {
    const Eigen::Matrix3Xd xe = disc.element_positions(e, x);
    double J = 0.0, vm = 0.0, volume = 0.0;
    for (int q = 0; q < disc.quadrature_points(); ++q) {
      const Mat3 F = xe * disc.gradients(e, q);
      const double w = disc.weight(e, q);
      J += w * F.determinant();
      if (material.in_domain(F) && F.determinant() > 0.0) {
        const Mat3 sigma = cauchy_stress(material, F);
        const Mat3 s = sigma - sigma.trace() / 3.0 * Mat3::Identity();
        vm += w * std::sqrt(1.5 * s.squaredNorm());
      } else {
        vm = std::numeric_limits<double>::quiet_NaN();
      }
      volume += w;
    }
    f.J(e) = J / volume;
    f.von_mises(e) = vm / volume;
  }
  return f;
}

RunViewer::RunViewer(const Scene& scene, std::shared_ptr<const Discretization> disc,
                     std::shared_ptr<const Material> material, ViewerOptions options)
    : scene_(&scene), disc_(std::move(disc)), material_(std::move(material)) {
  const VolumeMesh& mesh = disc_->mesh();
  surface_ = boundary_surface(mesh);
  std::vector<ViewerObject> objects;
  // The body's surface vertices are renumbered 0.. in surface_.vertices order.
  Eigen::VectorXi local = Eigen::VectorXi::Constant(mesh.num_vertices(), -1);
  for (std::size_t i = 0; i < surface_.vertices.size(); ++i) local(surface_.vertices[i]) = static_cast<int>(i);
  Eigen::MatrixX3i body(surface_.triangles.rows(), 3);
  for (Eigen::Index t = 0; t < body.rows(); ++t)
    for (int k = 0; k < 3; ++k) body(t, k) = local(surface_.triangles(t, k));
  objects.push_back({"body", ViewerRole::Body, body, kFieldNames});

  if (scene.mesh.embed) {
    try {
      const TriangleSurface render = read_triangle_surface(*scene.mesh.embed);
      embedding_ = embed_points(mesh, render.vertices);
      objects.push_back({"render_surface", ViewerRole::RenderSurface, render.faces, kFieldNames});
    } catch (const Error& e) {
      throw e.within(scene.file.string() + ": /mesh/embed");
    }
  }

  Eigen::AlignedBox3d focus;
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) focus.extend(mesh.vertices.row(v).transpose());
  for (std::size_t i = 0; i < scene.obstacles.size(); ++i) {
    const TriangleSurface s = scene.obstacles[i].shape->surface_mesh(focus);
    rigid_.push_back({s.vertices, i, false});
    objects.push_back({"obstacle " + scene.obstacles[i].name, ViewerRole::Obstacle, s.faces, {}});
  }
  if (scene.rig) {
    for (std::size_t i = 0; i < scene.rig->bones.size(); ++i) {
      const TriangleSurface s = bone_rest_surface(*scene.rig->bones[i].shape);
      rigid_.push_back({s.vertices, i, true});
      objects.push_back({"bone " + scene.rig->bones[i].name, ViewerRole::Bone, s.faces, {}});
    }
  }
  if (options.title == ViewerOptions{}.title) options.title = "Sinew: " + scene.file.filename().string();
  writer_ = std::make_unique<ViewerWriter>(std::move(objects), std::move(options));
}

void RunViewer::add_frame(int frame, double time, const Eigen::VectorXd& x) {
  const VolumeMesh& mesh = disc_->mesh();
  if (x.size() != 3 * mesh.num_vertices())
    throw Error(fmt::format("frame {} has {} position values for {} vertices", frame, x.size(), mesh.num_vertices()), "viewer");
  const ElementStressFields ef = element_stress_fields(*disc_, *material_, x);
  const Eigen::VectorXd J = nodal_average(*disc_, ef.J), vm = nodal_average(*disc_, ef.von_mises);

  std::vector<ViewerObjectFrame> frames;
  ViewerObjectFrame body;
  const auto n = static_cast<Eigen::Index>(surface_.vertices.size());
  body.positions.resize(n, 3);
  body.fields = {Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (Eigen::Index i = 0; i < n; ++i) {
    const int v = surface_.vertices[static_cast<std::size_t>(i)];
    body.positions.row(i) = x.segment<3>(3 * v).transpose();
    body.fields[0](i) = J(v), body.fields[1](i) = vm(v);
  }
  frames.push_back(std::move(body));

  if (embedding_) {
    ViewerObjectFrame render;
    render.positions = embedding_->positions(x);
    render.fields = {interpolate_at_points(*embedding_, J), interpolate_at_points(*embedding_, vm)};
    frames.push_back(std::move(render));
  }

  for (const Rigid& r : rigid_) {
    ViewerObjectFrame f;
    f.positions.resize(r.rest.rows(), 3);
    if (r.bone) {
      const Affine34 A = scene_->rig->bones[r.index].transform_at(frame);
      for (Eigen::Index i = 0; i < r.rest.rows(); ++i) f.positions.row(i) = apply(A, r.rest.row(i).transpose()).transpose();
    } else {
      const RigidTransform T = transform_at(scene_->obstacles[r.index].motion, frame);
      for (Eigen::Index i = 0; i < r.rest.rows(); ++i) f.positions.row(i) = T.apply(r.rest.row(i).transpose()).transpose();
    }
    frames.push_back(std::move(f));
  }
  writer_->add_frame(frame, time, frames);
}

std::vector<RunFrame> read_run_frames(const std::filesystem::path& out, Eigen::Index vertices) {
  const std::filesystem::path pvd = out / "simulation.pvd";
  std::ifstream in(pvd);
  if (!in) throw Error("cannot read the run's frame collection (was the run written with \"vtu\": true?)", pvd.string());
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  static const std::regex dataset(R"re(<DataSet\s+timestep="([^"]*)"[^>]*\sfile="([^"]*)")re");
  static const std::regex numbered(R"(frame_(\d+)\.vtu)");
  std::vector<RunFrame> frames;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), dataset); it != std::sregex_iterator(); ++it) {
    const std::string file = (*it)[2];
    std::smatch m;
    if (!std::regex_match(file, m, numbered)) throw Error(fmt::format("unexpected frame file name '{}'", file), pvd.string());
    RunFrame f;
    f.frame = std::stoi(m[1]);
    try {
      f.time = std::stod((*it)[1]);
    } catch (const std::exception&) {
      throw Error(fmt::format("timestep '{}' of {} is not a number", (*it)[1].str(), file), pvd.string());
    }
    const VolumeMesh frame_mesh = read_vtu_mesh(out / file);
    if (frame_mesh.num_vertices() != vertices)
      throw Error(fmt::format("has {} vertices, the scene's mesh has {}", frame_mesh.num_vertices(), vertices),
                  (out / file).string());
    f.x = frame_mesh.rest_positions();
    frames.push_back(std::move(f));
  }
  if (frames.empty()) throw Error("lists no frames", pvd.string());
  std::stable_sort(frames.begin(), frames.end(), [](const RunFrame& a, const RunFrame& b) { return a.time < b.time; });
  return frames;
}

std::size_t write_run_viewer(const Scene& scene, const std::filesystem::path& out, ViewerOptions options) {
  auto disc = std::make_shared<const Discretization>(build_scene_mesh(scene), scene.file.string() + ": /mesh");
  RunViewer viewer(scene, disc, build_material(scene.material), std::move(options));
  for (const RunFrame& f : read_run_frames(out, disc->mesh().num_vertices())) viewer.add_frame(f.frame, f.time, f.x);
  viewer.finish(out / "viewer.html");
  return viewer.frames();
}

}  // namespace sinew
