#pragma once
// Strict reads of values from the run's own files (checkpoint.json, the per-frame records):
// they may have been damaged or edited, so every value is checked for its type and range and a
// problem is a sinew::Error naming the JSON path (the caller adds the file).
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "sinew/core/error.hpp"

namespace sinew::json_checks {

inline std::string kind(const nlohmann::json& j) {
  if (j.is_number_float()) return fmt::format("{}", j.get<double>());
  if (j.is_number()) return j.dump();
  return j.type_name();
}

inline const nlohmann::json& member(const nlohmann::json& j, const std::string& key, const std::string& path) {
  if (!j.is_object()) throw Error(fmt::format("must be an object, got {}", j.type_name()), path.empty() ? "/" : path);
  const auto it = j.find(key);
  if (it == j.end()) throw Error("missing", path + "/" + key);
  return *it;
}

// A whole number in [lo, hi]: 2.5, 1e300, "3" and 2^40 (for an int) are refused.
inline long long integer(const nlohmann::json& j, long long lo, long long hi, const std::string& path) {
  long long v = 0;
  if (j.is_number_unsigned()) {
    const auto u = j.get<unsigned long long>();
    if (u > static_cast<unsigned long long>(std::numeric_limits<long long>::max()))
      throw Error(fmt::format("must be a whole number from {} to {}, got {}", lo, hi, u), path);
    v = static_cast<long long>(u);
  } else if (j.is_number_integer()) {
    v = j.get<long long>();
  } else {
    throw Error(fmt::format("must be a whole number from {} to {}, got {}", lo, hi, kind(j)), path);
  }
  if (v < lo || v > hi) throw Error(fmt::format("must be a whole number from {} to {}, got {}", lo, hi, v), path);
  return v;
}

// A number; null reads as NaN (nlohmann writes a NaN as null).
inline double number(const nlohmann::json& j, const std::string& path) {
  if (j.is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (!j.is_number()) throw Error(fmt::format("must be a number, got {}", kind(j)), path);
  return j.get<double>();
}

inline bool boolean(const nlohmann::json& j, const std::string& path) {
  if (!j.is_boolean()) throw Error(fmt::format("must be true or false, got {}", kind(j)), path);
  return j.get<bool>();
}

inline std::string string(const nlohmann::json& j, const std::string& path) {
  if (!j.is_string()) throw Error(fmt::format("must be a string, got {}", kind(j)), path);
  return j.get<std::string>();
}

inline const nlohmann::json& array(const nlohmann::json& j, const std::string& path) {
  if (!j.is_array()) throw Error(fmt::format("must be an array, got {}", kind(j)), path);
  return j;
}

}  // namespace sinew::json_checks
