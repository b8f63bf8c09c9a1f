#include "sinew/scene/json_reader.hpp"

#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

JsonObject::JsonObject(const nlohmann::json& json, std::string file, std::string path)
    : json_(json), file_(std::move(file)), path_(std::move(path)) {
  if (!json_.is_object()) throw Error(fmt::format("must be an object, got {}", json_.type_name()), file_ + ": " + (path_.empty() ? "/" : path_));
}

bool JsonObject::has(const std::string& key) const { return json_.contains(key); }

void JsonObject::fail(const std::string& key, const std::string& reason) const {
  throw Error(reason, file_ + ": " + path_of(key));
}

const nlohmann::json& JsonObject::get(const std::string& key) {
  read_.insert(key);
  const auto it = json_.find(key);
  if (it == json_.end()) fail(key, "required field is missing");
  return *it;
}

const nlohmann::json& JsonObject::raw(const std::string& key) { return get(key); }

JsonObject JsonObject::object(const std::string& key) {
  const auto& j = get(key);
  if (!j.is_object()) fail(key, fmt::format("must be an object, got {}", j.type_name()));
  return JsonObject(j, file_, path_of(key));
}

std::vector<JsonObject> JsonObject::objects(const std::string& key) {
  const auto& j = get(key);
  if (!j.is_array()) fail(key, fmt::format("must be an array, got {}", j.type_name()));
  std::vector<JsonObject> out;
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string p = fmt::format("{}/{}", path_of(key), i);
    if (!j[i].is_object()) throw Error(fmt::format("must be an object, got {}", j[i].type_name()), file_ + ": " + p);
    out.emplace_back(j[i], file_, p);
  }
  return out;
}

double JsonObject::number(const std::string& key) {
  const auto& j = get(key);
  if (!j.is_number()) fail(key, fmt::format("must be a number, got {}", j.type_name()));
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail(key, "must be a finite number");
  return v;
}

double JsonObject::number(const std::string& key, double fallback) {
  return has(key) ? number(key) : (read_.insert(key), fallback);
}

double JsonObject::positive(const std::string& key) {
  const double v = number(key);
  if (!(v > 0.0)) fail(key, fmt::format("must be a positive number, got {}", v));
  return v;
}

double JsonObject::positive(const std::string& key, double fallback) {
  return has(key) ? positive(key) : (read_.insert(key), fallback);
}

int JsonObject::integer(const std::string& key, int min_value) {
  const auto& j = get(key);
  if (!j.is_number_integer()) fail(key, fmt::format("must be an integer, got {}", j.dump()));
  const auto v = j.get<long long>();
  if (v < min_value) fail(key, fmt::format("must be at least {}, got {}", min_value, v));
  if (v > 2147483647LL) fail(key, fmt::format("is too large: {}", v));
  return static_cast<int>(v);
}

int JsonObject::integer(const std::string& key, int min_value, int fallback) {
  return has(key) ? integer(key, min_value) : (read_.insert(key), fallback);
}

bool JsonObject::boolean(const std::string& key, bool fallback) {
  if (!has(key)) return read_.insert(key), fallback;
  const auto& j = get(key);
  if (!j.is_boolean()) fail(key, fmt::format("must be true or false, got {}", j.dump()));
  return j.get<bool>();
}

std::string JsonObject::string(const std::string& key) {
  const auto& j = get(key);
  if (!j.is_string()) fail(key, fmt::format("must be a string, got {}", j.type_name()));
  return j.get<std::string>();
}

std::string JsonObject::string(const std::string& key, const std::string& fallback) {
  return has(key) ? string(key) : (read_.insert(key), fallback);
}

std::string JsonObject::choice(const std::string& key, const std::vector<std::string>& allowed,
                               const std::string& fallback) {
  const std::string v = string(key, fallback);
  for (const auto& a : allowed)
    if (a == v) return v;
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
  fail(key, fmt::format("unknown value '{}' (expected one of: {})", v, list));
}

Eigen::Vector3d JsonObject::vec3(const std::string& key) {
  const auto& j = get(key);
  if (!j.is_array() || j.size() != 3) fail(key, fmt::format("must be an array of 3 numbers, got {}", j.dump()));
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number()) fail(key, fmt::format("must be an array of 3 numbers, got {}", j.dump()));
    v(i) = j[i].get<double>();
    if (!std::isfinite(v(i))) fail(key, "must contain finite numbers");
  }
  return v;
}

Eigen::Vector3d JsonObject::vec3(const std::string& key, const Eigen::Vector3d& fallback) {
  return has(key) ? vec3(key) : (read_.insert(key), fallback);
}

Eigen::Vector3i JsonObject::ivec3(const std::string& key, int min_value) {
  const auto& j = get(key);
  if (!j.is_array() || j.size() != 3) fail(key, fmt::format("must be an array of 3 integers, got {}", j.dump()));
  Eigen::Vector3i v;
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number_integer()) fail(key, fmt::format("must be an array of 3 integers, got {}", j.dump()));
    const auto x = j[i].get<long long>();
    if (x < min_value || x > 1000000) fail(key, fmt::format("entries must be in [{}, 1000000], got {}", min_value, x));
    v(i) = static_cast<int>(x);
  }
  return v;
}

std::vector<int> JsonObject::int_list(const std::string& key, int min_value) {
  const auto& j = get(key);
  if (!j.is_array()) fail(key, fmt::format("must be an array of integers, got {}", j.type_name()));
  std::vector<int> out;
  for (size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_number_integer()) fail(key, fmt::format("entry {} must be an integer, got {}", i, j[i].dump()));
    const auto x = j[i].get<long long>();
    if (x < min_value || x > 2147483647LL) fail(key, fmt::format("entry {} out of range: {}", i, x));
    out.push_back(static_cast<int>(x));
  }
  return out;
}

void JsonObject::finish() const {
  for (auto it = json_.begin(); it != json_.end(); ++it) {
    if (!read_.count(it.key())) {
      throw Error("unknown field (check the spelling; see docs/scene-format.md)", file_ + ": " + path_of(it.key()));
    }
  }
}

}  // namespace sinew
