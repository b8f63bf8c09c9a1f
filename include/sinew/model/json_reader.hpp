#pragma once
// Strict, path-aware access to a JSON object: every field read is checked for type, finiteness
// and range, and finish() rejects keys that nothing read. Errors name the file and JSON path,
// e.g. "scene.json: /solver/newton/tolerance: must be a positive finite number, got -1".
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace sinew {

class JsonObject {
 public:
  // `file` names the source in errors; `path` is the JSON pointer of this object.
  JsonObject(const nlohmann::json& json, std::string file, std::string path = "");

  // Declares the keys this object may hold and rejects any other at once, listing the
  // allowed ones, so a misspelt key is reported before whatever its absence would cause.
  void allow(const std::vector<std::string>& keys);

  bool has(const std::string& key) const;
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  // The JSON pointer of a member ("" names this object itself).
  std::string path_of(const std::string& key) const;
  [[noreturn]] void fail(const std::string& key, const std::string& reason) const;

  const nlohmann::json& raw(const std::string& key);  // marks it read; throws if missing
  JsonObject object(const std::string& key);
  std::vector<JsonObject> objects(const std::string& key);  // array of objects

  double number(const std::string& key);
  double number(const std::string& key, double fallback);
  double positive(const std::string& key);
  double positive(const std::string& key, double fallback);
  int integer(const std::string& key, int min_value);
  int integer(const std::string& key, int min_value, int fallback);
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key);
  std::string string(const std::string& key, const std::string& fallback);
  std::string choice(const std::string& key, const std::vector<std::string>& allowed,
                     const std::string& fallback);
  Eigen::Vector3d vec3(const std::string& key);
  Eigen::Vector3d vec3(const std::string& key, const Eigen::Vector3d& fallback);
  Eigen::Vector3i ivec3(const std::string& key, int min_value);
  std::vector<int> int_list(const std::string& key, int min_value);

  // Throws for the first key that was never read.
  void finish() const;

 private:
  const nlohmann::json& get(const std::string& key);
  [[noreturn]] void unknown(const std::string& key) const;
  const nlohmann::json& json_;
  std::string file_, path_;
  std::set<std::string> read_;
  std::vector<std::string> allowed_;
};

}  // namespace sinew
