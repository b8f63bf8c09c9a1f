#include "sinew/io/viewer_writer.hpp"

#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/io/base64.hpp"
#include "sinew/io/vtk_writer.hpp"  // xml_escape

#ifndef SINEW_VIEWER_SCRIPT
#define SINEW_VIEWER_SCRIPT ""
#endif

namespace sinew {
namespace {

Eigen::Vector4f role_color(ViewerRole role) {
  switch (role) {
    case ViewerRole::Body: return {0.80f, 0.45f, 0.35f, 1.0f};
    case ViewerRole::RenderSurface: return {0.85f, 0.60f, 0.50f, 1.0f};
    case ViewerRole::Obstacle: return {0.55f, 0.60f, 0.70f, 0.45f};
    case ViewerRole::Bone: return {0.93f, 0.90f, 0.80f, 1.0f};
  }
  return {0.8f, 0.8f, 0.8f, 1.0f};
}

// Text placed inside <script> must not close the element early.
std::string script_safe(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') out += '\\';  // "<\/"
  }
  return out;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw Error("cannot read the viewer script (built from viewer/ by the build when npm is installed; run scripts/setup)",
                path.string());
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

const char* to_string(ViewerRole role) {
  switch (role) {
    case ViewerRole::Body: return "body";
    case ViewerRole::RenderSurface: return "render_surface";
    case ViewerRole::Obstacle: return "obstacle";
    case ViewerRole::Bone: return "bone";
  }
  return "body";
}

std::filesystem::path default_viewer_script() {
  if (const char* env = std::getenv("SINEW_VIEWER_SCRIPT"); env && *env) return env;
  return SINEW_VIEWER_SCRIPT;
}

ViewerWriter::ViewerWriter(std::vector<ViewerObject> objects, ViewerOptions options)
    : objects_(std::move(objects)), options_(std::move(options)) {
  if (objects_.empty()) throw Error("no objects to show", "viewer");
  if (!(options_.frames_per_second > 0.0)) throw Error("frames_per_second must be positive", "viewer");
  std::set<std::string> names;
  for (const ViewerObject& o : objects_) {
    if (o.name.empty()) throw Error("an object has no name", "viewer");
    if (!names.insert(o.name).second) throw Error(fmt::format("two objects are named '{}'", o.name), "viewer");
    if (o.triangles.rows() == 0) throw Error(fmt::format("object '{}' has no triangles", o.name), "viewer");
    AnimatedMesh m;
    m.name = o.name;
    m.role = to_string(o.role);
    m.triangles = o.triangles;
    m.field_names = o.field_names;
    m.color = role_color(o.role);
    scene_.meshes.push_back(std::move(m));
  }
  scene_.z_up = options_.z_up;
}

void ViewerWriter::add_frame(int frame, double time, const std::vector<ViewerObjectFrame>& objects) {
  if (objects.size() != objects_.size())
    throw Error(fmt::format("frame {} gives {} objects, the viewer has {}", frame, objects.size(), objects_.size()), "viewer");
  if (!scene_.times.empty() && !(time > scene_.times.back()))
    throw Error(fmt::format("frame {} has time {}, not after the previous frame's {}", frame, time, scene_.times.back()),
                "viewer");
  // Checked whole before anything is stored, so a rejected frame leaves the writer as it was.
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const ViewerObject& o = objects_[i];
    const ViewerObjectFrame& f = objects[i];
    const std::string where = fmt::format("viewer object '{}', frame {}", o.name, frame);
    const Eigen::Index nv = scene_.meshes[i].positions.empty() ? f.positions.rows() : scene_.meshes[i].positions[0].rows();
    if (f.positions.rows() != nv) throw Error(fmt::format("{} vertices, earlier frames have {}", f.positions.rows(), nv), where);
    if (o.triangles.maxCoeff() >= nv || o.triangles.minCoeff() < 0)
      throw Error(fmt::format("a triangle refers to a vertex outside 0..{}", nv - 1), where);
    if (!f.positions.allFinite()) throw Error("non-finite position", where);
    if (f.fields.size() != o.field_names.size())
      throw Error(fmt::format("{} fields given, expected {}", f.fields.size(), o.field_names.size()), where);
    for (std::size_t k = 0; k < f.fields.size(); ++k) {
      if (f.fields[k].size() != nv)
        throw Error(fmt::format("field '{}' has {} values for {} vertices", o.field_names[k], f.fields[k].size(), nv), where);
      if (!f.fields[k].allFinite()) throw Error(fmt::format("field '{}' has a non-finite value", o.field_names[k]), where);
    }
  }
  for (std::size_t i = 0; i < objects.size(); ++i) {
    AnimatedMesh& m = scene_.meshes[i];
    m.positions.push_back(objects[i].positions.cast<float>());
    if (m.field_names.empty()) continue;
    std::vector<Eigen::VectorXf> fields;
    for (const Eigen::VectorXd& v : objects[i].fields) fields.push_back(v.cast<float>());
    m.fields.push_back(std::move(fields));
  }
  scene_.frame_numbers.push_back(frame);
  scene_.times.push_back(time);
}

std::string viewer_html(const std::string& glb, const std::string& script, const ViewerOptions& options) {
  std::string encoded;
  Base64Encoder encoder(encoded);
  encoder.append(glb.data(), glb.size());
  encoder.finish();
  const nlohmann::json settings = {{"title", options.title}, {"fps", options.frames_per_second}};
  return fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>{}</title>\n"
      "<meta name=\"generator\" content=\"Sinew\">\n</head>\n<body>\n"
      "<script type=\"application/json\" id=\"sinew-settings\">{}</script>\n"
      "<script type=\"application/octet-stream\" id=\"sinew-glb\">{}</script>\n"
      "<script>\n{}\n</script>\n</body>\n</html>\n",
      xml_escape(options.title), script_safe(settings.dump()), encoded, script_safe(script));
}

void ViewerWriter::finish(const std::filesystem::path& html) const {
  if (scene_.frame_numbers.empty()) throw Error("no frames were added", html.string());
  const std::filesystem::path script_path = options_.script.empty() ? default_viewer_script() : options_.script;
  if (script_path.empty()) throw Error("this build has no viewer script (npm was not found when it was configured)", html.string());
  const std::string script = read_text(script_path);
  std::string glb;
  try {
    glb = glb_bytes(scene_);
  } catch (const Error& e) {
    throw e.within(html.string());
  }
  std::filesystem::path glb_path = html;
  glb_path.replace_extension(".glb");
  write_file_atomically(glb_path, [&](std::ostream& os) { os.write(glb.data(), static_cast<std::streamsize>(glb.size())); });
  const std::string page = viewer_html(glb, script, options_);
  write_file_atomically(html, [&](std::ostream& os) { os.write(page.data(), static_cast<std::streamsize>(page.size())); });
}

}  // namespace sinew
