#include "sinew/model/rig_reader.hpp"

#include <optional>
#include <vector>

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <numbers>
#include <nlohmann/json.hpp>

#include "sinew/core/error.hpp"
#include "sinew/model/json_reader.hpp"

namespace sinew {
namespace {

// {"axis": [...], "degrees": d, "center": [...]}: a rotation about an axis through `center`
// (default the origin), the pivot kept apart so that interpolation turns about it.
// Returns whether the rotation names its centre.
bool parse_rotation(JsonObject r, BoneKey& key) {
  r.allow({"axis", "degrees", "center"});
  const bool has_center = r.has("center");
  const Eigen::Vector3d axis = r.vec3("axis");
  if (!(axis.norm() > 0.0)) r.fail("axis", "must be non-zero");
  const double degrees = r.number("degrees");
  const Eigen::Vector3d center = r.vec3("center", Eigen::Vector3d::Zero());
  key.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, axis.normalized()));
  key.center = center;  // x = R (X - c) + c + t
  r.finish();
  return has_center;
}

Affine34 parse_matrix(JsonObject& key) {
  const nlohmann::json& m = key.raw("matrix");
  const std::string reason = "must be 3 rows of 4 finite numbers (the rows of [A | t])";
  if (!m.is_array() || m.size() != 3) key.fail("matrix", reason);
  Affine34 A;
  for (int r = 0; r < 3; ++r) {
    if (!m[r].is_array() || m[r].size() != 4) key.fail("matrix", reason);
    for (int c = 0; c < 4; ++c) {
      if (!m[r][c].is_number()) key.fail("matrix", reason);
      A(r, c) = m[r][c].get<double>();
      if (!std::isfinite(A(r, c))) key.fail("matrix", reason);
    }
  }
  return A;
}

Bone parse_bone(JsonObject o) {
  o.allow({"name", "capsule", "mesh", "motion", "keys"});
  Bone bone;
  bone.name = o.string("name");
  if (bone.name.empty()) o.fail("name", "must not be empty");
  if (o.has("mesh") == o.has("capsule")) o.fail(o.has("mesh") ? "mesh" : "capsule", "give exactly one of capsule and mesh");
  if (o.has("mesh")) {
    // Relative to the file the rig was read from (the rig file, or the scene for an inline rig).
    std::filesystem::path mesh = o.string("mesh");
    if (mesh.is_relative()) mesh = std::filesystem::path(o.file()).parent_path() / mesh;
    try {
      bone.shape = load_mesh_bone(mesh);
    } catch (const Error& e) {
      throw e.within(o.file() + ": " + o.path_of("mesh"));
    }
  } else {
    JsonObject c = o.object("capsule");
    c.allow({"a", "b", "radius"});
    bone.shape = std::make_shared<CapsuleShape>(c.vec3("a"), c.vec3("b"), c.positive("radius"));
    c.finish();
  }
  const std::string motion = o.choice("motion", {"rigid", "affine"}, "rigid");
  bone.motion = motion == "rigid" ? BoneMotion::Rigid : BoneMotion::Affine;
  std::vector<char> explicit_center;
  for (JsonObject key : o.objects("keys")) {
    BoneKey k;
    bool key_has_center = false;
    if (bone.motion == BoneMotion::Rigid) {
      key.allow({"frame", "translation", "rotation", "quaternion"});
    } else {
      key.allow({"frame", "matrix"});
    }
    k.frame = key.number("frame");
    if (!bone.keys.empty() && !(k.frame > bone.keys.back().frame))
      key.fail("frame", fmt::format("must be after the previous keyframe's ({} <= {})", k.frame, bone.keys.back().frame));
    if (bone.motion == BoneMotion::Rigid) {
      k.translation = key.vec3("translation", Eigen::Vector3d::Zero());
      if (key.has("rotation") && key.has("quaternion")) key.fail("quaternion", "give either rotation or quaternion, not both");
      if (key.has("rotation")) key_has_center = parse_rotation(key.object("rotation"), k);
      if (key.has("quaternion")) {
        const nlohmann::json& q = key.raw("quaternion");
        const std::string reason = "must be 4 finite numbers [w, x, y, z], not all zero";
        if (!q.is_array() || q.size() != 4) key.fail("quaternion", reason);
        double wxyz[4];
        for (int i = 0; i < 4; ++i) {
          if (!q[i].is_number()) key.fail("quaternion", reason);
          wxyz[i] = q[i].get<double>();
          if (!std::isfinite(wxyz[i])) key.fail("quaternion", reason);
        }
        k.rotation = Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
        if (!(k.rotation.norm() > 1e-12)) key.fail("quaternion", reason);
        k.rotation.normalize();
      }
    } else {
      k.affine = parse_matrix(key);
    }
    key.finish();
    bone.keys.push_back(k);
    explicit_center.push_back(key_has_center);
  }
  if (bone.keys.empty()) o.fail("keys", "needs at least one keyframe");
  o.finish();
  // Keys interpolate about their pivots; a key that names none (a rest key, a quaternion key)
  // takes the nearest earlier named pivot, else the next one, with its translation adjusted so
  // that its own pose is unchanged (R (X - c) + c + t' = R X + t). So {"frame": 0} followed by a
  // turn about the elbow turns about the elbow all the way.
  if (bone.motion == BoneMotion::Rigid) {
    for (size_t i = 0; i < bone.keys.size(); ++i) {
      if (explicit_center[i]) continue;
      std::optional<Eigen::Vector3d> pivot;
      for (size_t j = i; j-- > 0 && !pivot;)
        if (explicit_center[j]) pivot = bone.keys[j].center;
      for (size_t j = i + 1; j < bone.keys.size() && !pivot; ++j)
        if (explicit_center[j]) pivot = bone.keys[j].center;
      if (!pivot) continue;
      BoneKey& k = bone.keys[i];
      k.translation += k.rotation * *pivot - *pivot;
      k.center = *pivot;
    }
  }
  return bone;
}

}  // namespace

Rig parse_rig(JsonObject& o) {
  o.allow({"description", "binding", "spring_stiffness", "bones"});
  Rig rig;
  o.string("description", "");
  const std::string binding = o.choice("binding", {"hard", "springs"}, "hard");
  rig.binding = binding == "hard" ? BoneBinding::Hard : BoneBinding::Springs;
  if (rig.binding == BoneBinding::Springs) rig.spring_stiffness = o.positive("spring_stiffness");
  for (JsonObject b : o.objects("bones")) rig.bones.push_back(parse_bone(b));
  if (rig.bones.empty()) o.fail("bones", "needs at least one bone");
  for (size_t i = 0; i < rig.bones.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (rig.bones[i].name == rig.bones[j].name)
        throw Error(fmt::format("duplicate bone name \"{}\"", rig.bones[i].name), fmt::format("{}: {}/bones/{}/name", o.file(), o.path(), i));
  o.finish();
  validate_rig(rig, o.file() + (o.path().empty() ? "" : ": " + o.path()));
  return rig;
}

Rig parse_rig(const nlohmann::json& json, const std::filesystem::path& file, const std::string& path) {
  JsonObject o(json, file.string(), path);
  return parse_rig(o);
}

Rig load_rig(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) throw Error("is a directory, not a rig file", name);
  std::ifstream in(file);
  if (!in) throw Error("cannot open rig file (missing or unreadable)", name);
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("malformed JSON: {}", e.what()), name);
  }
  return parse_rig(json, file, "");
}

}  // namespace sinew
