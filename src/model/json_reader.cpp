#include "sinew/model/json_reader.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <functional>
#include <set>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// A value as it appeared, shortened for an error line: `string "abc"`, `array [1,2]`.
// Built piece by piece with a bounded depth and length, so a huge or deeply nested value costs
// no more than a short one (dump() would print all of it, recursively).
void preview(const nlohmann::json& j, std::string& out, int depth) {
  constexpr std::size_t kLength = 40;
  if (out.size() > kLength) return;
  if (!j.is_structured()) {
    out += j.dump();
    return;
  }
  const bool array = j.is_array();
  if (j.empty() || depth >= 2) {
    out += j.empty() ? (array ? "[]" : "{}") : (array ? "[...]" : "{...}");
    return;
  }
  out += array ? '[' : '{';
  bool first = true;
  for (auto it = j.begin(); it != j.end() && out.size() <= kLength; ++it) {
    if (!first) out += ',';
    first = false;
    if (!array) out += nlohmann::json(it.key()).dump() + ":";
    preview(*it, out, depth + 1);
  }
  out += array ? ']' : '}';
}

std::string describe(const nlohmann::json& j) {
  std::string text;
  preview(j, text, 0);
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

// Objects and arrays nest at most this deep in a file; deeper input is refused while parsing,
// before anything (copying, printing, freeing) can recurse that deep.
constexpr std::size_t kMaxJsonDepth = 64;


// Tracks the JSON pointer of the value being parsed (for errors nlohmann reports without
// one) and rejects duplicate keys, which nlohmann would otherwise resolve silently.
class PathTracker {
 public:
  explicit PathTracker(std::string file) : file_(std::move(file)) {}

  bool operator()(int /*depth*/, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using E = nlohmann::json::parse_event_t;
    if ((event == E::object_start || event == E::array_start) && stack_.size() >= kMaxJsonDepth)
      throw Error(fmt::format("nested more than {} levels deep (Sinew's formats need fewer than 10)", kMaxJsonDepth),
                  file_ + ": " + path());
    switch (event) {
      case E::object_start: stack_.push_back({false, 0, "", {}}); break;
      case E::array_start: stack_.push_back({true, 0, "", {}}); break;
      case E::key: {
        Frame& top = stack_.back();
        top.key = parsed.get<std::string>();
        if (!top.seen.insert(top.key).second) throw Error("duplicate key (JSON objects need unique keys)", file_ + ": " + path());
        break;
      }
      case E::object_end:
      case E::array_end: stack_.pop_back(); next_element(); break;
      case E::value: next_element(); break;
    }
    return true;
  }

  std::string path() const {
    std::string p;
    for (const auto& f : stack_) p += "/" + (f.array ? std::to_string(f.index) : f.key);
    return p.empty() ? "/" : p;
  }

 private:
  struct Frame {
    bool array;
    size_t index;
    std::string key;
    std::set<std::string> seen;
  };
  void next_element() {
    if (!stack_.empty() && stack_.back().array) ++stack_.back().index;
  }
  std::string file_;
  std::vector<Frame> stack_;
};

// nlohmann's "[json.exception.parse_error.101] parse error at line 3, column 5: ..." without
// the bracketed tag.
std::string without_tag(const std::string& what) {
  const auto close = what.find("] ");
  return what.rfind("[json.exception", 0) == 0 && close != std::string::npos ? what.substr(close + 2) : what;
}

}  // namespace

nlohmann::json parse_json(std::istream& in, const std::string& name) {
  PathTracker tracker(name);
  try {
    return nlohmann::json::parse(in, std::ref(tracker));
  } catch (const nlohmann::json::parse_error& e) {
    throw Error(fmt::format("malformed JSON: {}", without_tag(e.what())), name);
  } catch (const nlohmann::json::out_of_range& e) {
    // 1e999 and the like: "number overflow parsing '1e999'".
    throw Error(fmt::format("{} (numbers must be finite doubles)", without_tag(e.what())), name + ": " + tracker.path());
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("malformed JSON: {}", without_tag(e.what())), name + ": " + tracker.path());
  }
}

nlohmann::json read_json_file(const std::filesystem::path& file, const std::string& kind) {
  const std::string name = file.string();
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) throw Error(fmt::format("is a directory, not a {} file", kind), name);
  std::ifstream in(file);
  if (!in) throw Error(fmt::format("cannot open {} file (missing or unreadable)", kind), name);
  return parse_json(in, name);
}

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
