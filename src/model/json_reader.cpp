#include "sinew/model/json_reader.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// A value as it appeared, shortened for an error line: `string "abc"`, `array [1,2]`.
std::string describe(const nlohmann::json& j) {
  std::string text = j.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return fmt::format("{} {}", j.type_name(), text);
}

// nlohmann reads 1e999 as an infinite float; JSON has no NaN, so this is the only way a
// non-finite number reaches us.
const char* kNotFinite = "must be a finite number (the value overflows a double)";

// An integer in [min_value, max_value], or the reason it is not one.
std::optional<std::string> integer_problem(const nlohmann::json& j, long long min_value, long long max_value,
                                           long long& out) {
  if (j.is_number_unsigned()) {
    const auto u = j.get<unsigned long long>();
    if (u > static_cast<unsigned long long>(max_value)) return fmt::format("must be at most {}, got {}", max_value, u);
    out = static_cast<long long>(u);
  } else if (j.is_number_integer()) {
    out = j.get<long long>();
  } else {
    return fmt::format("must be an integer, got {}", describe(j));
  }
  if (out < min_value) return fmt::format("must be at least {}, got {}", min_value, out);
  if (out > max_value) return fmt::format("must be at most {}, got {}", max_value, out);
  return std::nullopt;
}

}  // namespace

JsonObject::JsonObject(const nlohmann::json& json, std::string file, std::string path)
    : json_(json), file_(std::move(file)), path_(std::move(path)) {
  if (!json_.is_object()) throw Error(fmt::format("must be an object, got {}", describe(json_)), file_ + ": " + (path_.empty() ? "/" : path_));
}

std::string JsonObject::path_of(const std::string& key) const {
  if (key.empty()) return path_.empty() ? "/" : path_;
  return path_ + "/" + key;
}

void JsonObject::allow(const std::vector<std::string>& keys) {
  allowed_ = keys;
  for (auto it = json_.begin(); it != json_.end(); ++it)
    if (std::find(keys.begin(), keys.end(), it.key()) == keys.end()) unknown(it.key());
}

void JsonObject::unknown(const std::string& key) const {
  std::string list;
  for (const auto& a : allowed_) list += (list.empty() ? "" : ", ") + a;
  throw Error(list.empty() ? std::string("unknown field (see docs/scene-format.md)")
                           : fmt::format("unknown field (expected one of: {})", list),
              file_ + ": " + path_of(key));
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
  if (!j.is_object()) fail(key, fmt::format("must be an object, got {}", describe(j)));
  return JsonObject(j, file_, path_of(key));
}

std::vector<JsonObject> JsonObject::objects(const std::string& key) {
  const auto& j = get(key);
  if (!j.is_array()) fail(key, fmt::format("must be an array, got {}", describe(j)));
  std::vector<JsonObject> out;
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string p = fmt::format("{}/{}", path_of(key), i);
    if (!j[i].is_object()) throw Error(fmt::format("must be an object, got {}", describe(j[i])), file_ + ": " + p);
    out.emplace_back(j[i], file_, p);
  }
  return out;
}

double JsonObject::number(const std::string& key) {
  const auto& j = get(key);
  if (!j.is_number()) fail(key, fmt::format("must be a number, got {}", describe(j)));
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail(key, kNotFinite);
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
  long long v = 0;
  if (const auto problem = integer_problem(get(key), min_value, INT_MAX, v)) fail(key, *problem);
  return static_cast<int>(v);
}

int JsonObject::integer(const std::string& key, int min_value, int fallback) {
  return has(key) ? integer(key, min_value) : (read_.insert(key), fallback);
}

bool JsonObject::boolean(const std::string& key, bool fallback) {
  if (!has(key)) return read_.insert(key), fallback;
  const auto& j = get(key);
  if (!j.is_boolean()) fail(key, fmt::format("must be true or false, got {}", describe(j)));
  return j.get<bool>();
}

std::string JsonObject::string(const std::string& key) {
  const auto& j = get(key);
  if (!j.is_string()) fail(key, fmt::format("must be a string, got {}", describe(j)));
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
  if (!j.is_array() || j.size() != 3) fail(key, fmt::format("must be an array of 3 numbers, got {}", describe(j)));
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    const std::string at = fmt::format("{}/{}", key, i);
    if (!j[i].is_number()) fail(at, fmt::format("must be a number, got {}", describe(j[i])));
    v(i) = j[i].get<double>();
    if (!std::isfinite(v(i))) fail(at, kNotFinite);
  }
  return v;
}

Eigen::Vector3d JsonObject::vec3(const std::string& key, const Eigen::Vector3d& fallback) {
  return has(key) ? vec3(key) : (read_.insert(key), fallback);
}

Eigen::Vector3i JsonObject::ivec3(const std::string& key, int min_value) {
  const auto& j = get(key);
  if (!j.is_array() || j.size() != 3) fail(key, fmt::format("must be an array of 3 integers, got {}", describe(j)));
  Eigen::Vector3i v;
  for (int i = 0; i < 3; ++i) {
    long long x = 0;
    if (const auto problem = integer_problem(j[i], min_value, 1000000, x)) fail(fmt::format("{}/{}", key, i), *problem);
    v(i) = static_cast<int>(x);
  }
  return v;
}

std::vector<int> JsonObject::int_list(const std::string& key, int min_value) {
  const auto& j = get(key);
  if (!j.is_array()) fail(key, fmt::format("must be an array of integers, got {}", describe(j)));
  std::vector<int> out;
  for (size_t i = 0; i < j.size(); ++i) {
    long long x = 0;
    if (const auto problem = integer_problem(j[i], min_value, INT_MAX, x)) fail(fmt::format("{}/{}", key, i), *problem);
    out.push_back(static_cast<int>(x));
  }
  return out;
}

void JsonObject::finish() const {
  for (auto it = json_.begin(); it != json_.end(); ++it) {
    if (read_.count(it.key())) continue;
    // Allowed in general but meaningless next to the fields actually given.
    if (std::find(allowed_.begin(), allowed_.end(), it.key()) != allowed_.end())
      fail(it.key(), "does not apply here (see docs/scene-format.md)");
    unknown(it.key());
  }
}

}  // namespace sinew
