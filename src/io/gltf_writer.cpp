#include "sinew/io/gltf_writer.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <ostream>

#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/io/field_colors.hpp"

namespace sinew {
namespace {

using nlohmann::json;

constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

// The BIN chunk and the accessors into it, one buffer view per accessor (4-byte aligned).
class BinaryBuilder {
 public:
  json accessors = json::array(), buffer_views = json::array();

  int add(const void* data, std::size_t bytes, int component, const char* type, std::size_t count, int target,
          json min = nullptr, json max = nullptr) {
    while (bin_.size() % 4 != 0) bin_.push_back('\0');
    json view = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes}};
    if (target != 0) view["target"] = target;
    buffer_views.push_back(view);
    bin_.append(static_cast<const char*>(data), bytes);
    json accessor = {{"bufferView", buffer_views.size() - 1}, {"componentType", component}, {"count", count}, {"type", type}};
    if (!min.is_null()) accessor["min"] = min, accessor["max"] = max;
    accessors.push_back(accessor);
    return static_cast<int>(accessors.size() - 1);
  }

  int add_vec3(const Eigen::MatrixX3f& rows, int target) {
    // Row-major bytes (x y z per vertex) and the bounds glTF requires for positions.
    Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor> packed = rows;
    const Eigen::RowVector3f lo = rows.colwise().minCoeff(), hi = rows.colwise().maxCoeff();
    return add(packed.data(), sizeof(float) * packed.size(), kFloat, "VEC3", rows.rows(), target,
               json{lo(0), lo(1), lo(2)}, json{hi(0), hi(1), hi(2)});
  }

  int add_scalars(const std::vector<float>& values, bool bounds) {
    json lo = nullptr, hi = nullptr;
    if (bounds && !values.empty()) {
      lo = json{*std::min_element(values.begin(), values.end())};
      hi = json{*std::max_element(values.begin(), values.end())};
    }
    return add(values.data(), sizeof(float) * values.size(), kFloat, "SCALAR", values.size(), 0, lo, hi);
  }

  std::string& bin() { return bin_; }

 private:
  std::string bin_;
};

void check_mesh(const AnimatedMesh& m, std::size_t frames) {
  const std::string where = fmt::format("glTF mesh '{}'", m.name);
  if (m.positions.size() != frames)
    throw Error(fmt::format("has {} frames of positions, the scene has {} frames", m.positions.size(), frames), where);
  if (m.triangles.rows() == 0) throw Error("has no triangles", where);
  const Eigen::Index nv = m.positions[0].rows();
  if (m.triangles.minCoeff() < 0 || m.triangles.maxCoeff() >= nv)
    throw Error(fmt::format("a triangle refers to a vertex outside 0..{}", nv - 1), where);
  if (m.fields.size() != (m.field_names.empty() ? 0 : frames) && !(m.field_names.empty() && m.fields.empty()))
    throw Error(fmt::format("has fields for {} frames, the scene has {} frames", m.fields.size(), frames), where);
  for (std::size_t f = 0; f < frames; ++f) {
    if (m.positions[f].rows() != nv)
      throw Error(fmt::format("frame {} has {} vertices, frame 0 has {}", f, m.positions[f].rows(), nv), where);
    if (!m.positions[f].allFinite()) throw Error(fmt::format("frame {} has a non-finite position", f), where);
    if (m.field_names.empty()) continue;
    if (m.fields[f].size() != m.field_names.size())
      throw Error(fmt::format("frame {} has {} fields, expected {}", f, m.fields[f].size(), m.field_names.size()), where);
    for (std::size_t k = 0; k < m.field_names.size(); ++k) {
      if (m.fields[f][k].size() != nv)
        throw Error(fmt::format("field '{}' of frame {} has {} values for {} vertices", m.field_names[k], f,
                                m.fields[f][k].size(), nv),
                    where);
      if (!m.fields[f][k].allFinite())
        throw Error(fmt::format("field '{}' of frame {} has a non-finite value", m.field_names[k], f), where);
    }
  }
}

}  // namespace

std::string glb_bytes(const AnimatedScene& scene) {
  const std::size_t frames = scene.frame_numbers.size();
  if (frames == 0) throw Error("no frames", "glTF scene");
  if (scene.meshes.empty()) throw Error("no meshes", "glTF scene");
  if (scene.times.size() != frames)
    throw Error(fmt::format("{} times for {} frames", scene.times.size(), frames), "glTF scene");
  std::vector<float> times(scene.times.begin(), scene.times.end());
  for (std::size_t f = 0; f < frames; ++f) {
    if (!std::isfinite(times[f]) || (f > 0 && !(times[f] > times[f - 1])))
      throw Error(fmt::format("time of frame {} ({}) does not increase (as a 32-bit float)", f, scene.times[f]),
                  "glTF scene");
  }
  for (const AnimatedMesh& m : scene.meshes) check_mesh(m, frames);

  BinaryBuilder b;
  json meshes = json::array(), nodes = json::array(), materials = json::array(), channels = json::array(),
       samplers = json::array();
  json root = {{"name", "sinew"}, {"children", json::array()}};
  // -90 degrees about x: +z (Sinew's up) becomes +y (glTF's up).
  if (scene.z_up) root["rotation"] = {-std::sqrt(0.5), 0.0, 0.0, std::sqrt(0.5)};
  nodes.push_back(root);
  const int time_accessor = frames > 1 ? b.add_scalars(times, true) : -1;

  for (const AnimatedMesh& m : scene.meshes) {
    Eigen::Matrix<std::uint32_t, Eigen::Dynamic, 3, Eigen::RowMajor> tri = m.triangles.cast<std::uint32_t>();
    json primitive = {{"mode", 4}, {"material", materials.size()}};
    primitive["indices"] = b.add(tri.data(), sizeof(std::uint32_t) * tri.size(), kUnsignedInt, "SCALAR", tri.size(),
                                 kElementArrayBuffer);
    primitive["attributes"] = {{"POSITION", b.add_vec3(m.positions[0], kArrayBuffer)}};

    json extras = {{"role", m.role}, {"fields", json::object()}, {"field_ranges", json::object()}};
    for (std::size_t k = 0; k < m.field_names.size(); ++k) {
      json per_frame = json::array();
      float lo = std::numeric_limits<float>::infinity(), hi = -lo;
      for (std::size_t f = 0; f < frames; ++f) {
        const Eigen::VectorXf& v = m.fields[f][k];
        lo = std::min(lo, v.minCoeff()), hi = std::max(hi, v.maxCoeff());
        per_frame.push_back(b.add_scalars(std::vector<float>(v.data(), v.data() + v.size()), false));
      }
      extras["fields"][m.field_names[k]] = per_frame;
      extras["field_ranges"][m.field_names[k]] = {lo, hi};
      if (k == 0) {
        const Eigen::MatrixX3f colors = field_colors(m.fields[0][0], lo, hi);
        primitive["attributes"]["COLOR_0"] = b.add_vec3(colors, kArrayBuffer);
      }
    }

    // Morph targets only for meshes that move (a static obstacle is stored once).
    bool moves = false;
    for (std::size_t f = 1; f < frames && !moves; ++f) moves = m.positions[f] != m.positions[0];
    json mesh = {{"name", m.name}, {"extras", extras}};
    const int node = static_cast<int>(nodes.size());
    if (moves) {
      primitive["targets"] = json::array();
      for (std::size_t f = 1; f < frames; ++f) {
        const Eigen::MatrixX3f delta = m.positions[f] - m.positions[0];
        primitive["targets"].push_back({{"POSITION", b.add_vec3(delta, kArrayBuffer)}});
      }
      mesh["weights"] = std::vector<float>(frames - 1, 0.0f);
      // Frame f shows target f (frame 0: no target): row f of the weights is the unit vector e_f.
      std::vector<float> weights(frames * (frames - 1), 0.0f);
      for (std::size_t f = 1; f < frames; ++f) weights[f * (frames - 1) + (f - 1)] = 1.0f;
      samplers.push_back({{"input", time_accessor}, {"output", b.add_scalars(weights, false)}, {"interpolation", "STEP"}});
      channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", node}, {"path", "weights"}}}});
    }
    mesh["primitives"] = json::array({primitive});
    meshes.push_back(mesh);
    nodes.push_back({{"name", m.name}, {"mesh", meshes.size() - 1}});
    nodes[0]["children"].push_back(node);

    // COLOR_0 multiplies the base colour: with a field the base is white (the field's colours
    // as they are) and the object's own colour is kept in extras for a page showing no field.
    const Eigen::Vector4f base = m.field_names.empty() ? m.color : Eigen::Vector4f(1.0f, 1.0f, 1.0f, m.color(3));
    if (!m.field_names.empty()) meshes.back()["extras"]["base_color"] = {m.color(0), m.color(1), m.color(2), m.color(3)};
    json material = {{"name", m.name},
                     {"doubleSided", true},
                     {"pbrMetallicRoughness",
                      {{"baseColorFactor", {base(0), base(1), base(2), base(3)}},
                       {"metallicFactor", 0.0},
                       {"roughnessFactor", 0.8}}}};
    if (m.color(3) < 1.0f) material["alphaMode"] = "BLEND";
    materials.push_back(material);
  }

  json gltf = {{"asset", {{"version", "2.0"}, {"generator", scene.generator}}},
               {"scene", 0},
               {"scenes", {{{"name", "sinew"}, {"nodes", {0}}}}},
               {"nodes", nodes},
               {"meshes", meshes},
               {"materials", materials},
               {"accessors", b.accessors},
               {"bufferViews", b.buffer_views},
               {"extras", {{"sinew", {{"frames", scene.frame_numbers}, {"times", scene.times}}}}}};
  json stops = json::array();
  for (const Eigen::Vector3f& c : field_color_stops()) stops.push_back({c(0), c(1), c(2)});
  gltf["extras"]["sinew"]["color_stops"] = stops;
  std::string& bin = b.bin();
  while (bin.size() % 4 != 0) bin.push_back('\0');
  gltf["buffers"] = {{{"byteLength", bin.size()}}};
  if (!channels.empty()) gltf["animations"] = {{{"name", "frames"}, {"channels", channels}, {"samplers", samplers}}};

  std::string text = gltf.dump();
  while (text.size() % 4 != 0) text.push_back(' ');
  const std::uint64_t total = 12 + 8 + text.size() + 8 + bin.size();
  if (total > 0xFFFFFFFFull) throw Error(fmt::format("the file would have {} bytes, over glTF's 4 GiB", total), "glTF scene");

  std::string glb;
  glb.reserve(total);
  auto u32 = [&](std::uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };  // glTF is little-endian
  static_assert(std::endian::native == std::endian::little, "the GLB writer assumes a little-endian machine");
  u32(0x46546C67), u32(2), u32(static_cast<std::uint32_t>(total));
  u32(static_cast<std::uint32_t>(text.size())), u32(0x4E4F534A);
  glb += text;
  u32(static_cast<std::uint32_t>(bin.size())), u32(0x004E4942);
  glb += bin;
  return glb;
}

void write_glb(const std::filesystem::path& path, const AnimatedScene& scene) {
  std::string bytes;
  try {
    bytes = glb_bytes(scene);
  } catch (const Error& e) {
    throw e.within(path.string());
  }
  write_file_atomically(path, [&](std::ostream& os) { os.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
}

}  // namespace sinew
