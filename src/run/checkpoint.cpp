#include "sinew/run/checkpoint.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <fstream>

#include "json_checks.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/model/json_reader.hpp"

namespace sinew {
namespace {

namespace fs = std::filesystem;
using namespace json_checks;

constexpr int kFormat = 3;

// 64-bit FNV-1a over n more bytes.
std::uint64_t fnv1a(std::uint64_t hash, const char* bytes, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    hash ^= static_cast<unsigned char>(bytes[i]);
    hash *= 1099511628211ull;
  }
  return hash;
}
constexpr std::uint64_t kFnvOffset = 14695981039346656037ull;

// Size and 64-bit FNV-1a hash of a file's bytes, read in blocks (a large mesh is not held twice).
std::string fingerprint_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read the file to fingerprint it for the checkpoint", path.string());
  std::uint64_t hash = kFnvOffset, size = 0;
  std::vector<char> block(1 << 16);
  while (in) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    const auto n = static_cast<std::size_t>(in.gcount());
    hash = fnv1a(hash, block.data(), n);
    size += n;
  }
  if (in.bad()) throw Error("read failed while fingerprinting it for the checkpoint", path.string());
  return fmt::format("{}:{:016x}", size, hash);
}

std::string fingerprint_text(const std::string& text) {
  return fmt::format("{}:{:016x}", text.size(), fnv1a(kFnvOffset, text.data(), text.size()));
}

Eigen::VectorXd read_vector(const nlohmann::json& j, const char* key, Eigen::Index dofs) {
  const std::string path = std::string("/") + key;
  const nlohmann::json& a = array(member(j, key, ""), path);
  if (static_cast<Eigen::Index>(a.size()) != dofs)
    throw Error(fmt::format("has {} values, the scene's mesh has {} DOFs (the checkpoint belongs to a different mesh)",
                            a.size(), dofs),
                path);
  Eigen::VectorXd v(dofs);
  for (Eigen::Index i = 0; i < dofs; ++i) {
    const nlohmann::json& e = a[static_cast<std::size_t>(i)];
    if (!e.is_number()) throw Error(fmt::format("must be a number, got {}", kind(e)), fmt::format("{}/{}", path, i));
    v(i) = e.get<double>();
  }
  return v;
}

}  // namespace

RunFingerprint fingerprint_run(const Scene& scene) {
  RunFingerprint f;
  // A scene built in memory (the Python module's dicts, tests) has no file: its JSON is the input.
  std::error_code ec;
  f.scene = fs::exists(scene.file, ec) ? fingerprint_file(scene.file) : fingerprint_text(scene.text);
  const fs::path folder = scene.file.parent_path();
  for (const fs::path& path : scene_input_files(scene)) {
    // Named relative to the scene's folder, so a run resumed from another working directory
    // (the same files under other relative paths) still matches.
    const std::string name = (folder.empty() ? path : path.lexically_proximate(folder)).generic_string();
    f.inputs.push_back({name, path, fingerprint_file(path)});
  }
  return f;
}

bool has_checkpoint(const fs::path& out) {
  std::error_code ec;
  return fs::exists(out / "checkpoint.json", ec);
}

void write_checkpoint(const fs::path& out, const RunFingerprint& fingerprint, const Integrator& integrator,
                      const Checkpoint& c) {
  nlohmann::json inputs = nlohmann::json::object();
  for (const auto& input : fingerprint.inputs) inputs[input.name] = input.fingerprint;
  nlohmann::json j = {{"format", kFormat},
                      {"integrator", integrator.name()},
                      {"scene_fingerprint", fingerprint.scene},
                      {"inputs", inputs},
                      {"frame", c.frame},
                      {"integrator_state", c.integrator_state}};
  j["x"] = std::vector<double>(c.state.x.data(), c.state.x.data() + c.state.x.size());
  if (integrator.dynamic()) j["v"] = std::vector<double>(c.state.v.data(), c.state.v.data() + c.state.v.size());
  write_file_atomically(out / "checkpoint.json", [&](std::ostream& os) { os << j.dump() << '\n'; });
}

Checkpoint read_checkpoint(const fs::path& out, const RunFingerprint& fingerprint, const Integrator& integrator,
                           Eigen::Index dofs, int frames_requested) {
  const fs::path path = out / "checkpoint.json";
  const std::string file = path.string();
  if (!has_checkpoint(out)) throw Error("no checkpoint to resume from (run without --resume first)", file);
  // The scene reader's parser: nesting depth bounded, duplicate keys refused, errors with paths.
  const nlohmann::json j = read_json_file(path, "checkpoint");
  // Problems inside the checkpoint name it and the JSON path; a changed input names that file.
  auto in_checkpoint = [&](const auto& read) {
    try {
      read();
    } catch (const Error& e) {
      throw e.within(file);
    }
  };
  const nlohmann::json* inputs = nullptr;
  in_checkpoint([&] {
    if (!j.is_object()) throw Error(fmt::format("must be an object, got {}", kind(j)), "/");
    const auto written_by = j.find("integrator");
    const std::string by = written_by != j.end() && written_by->is_string() ? written_by->get<std::string>() : "";
    const auto format = j.find("format");
    const bool ours = format != j.end() && *format == kFormat;
    if (!ours || by != integrator.name())
      throw Error(fmt::format("checkpoint was written by {} run, this scene runs {} ({}); run again without --resume",
                              by.empty() || !ours ? "an older or another kind of" : "a " + by, integrator.name(),
                              integrator.description()));
    if (member(j, "scene_fingerprint", "") != fingerprint.scene)
      throw Error("the scene file changed since the checkpoint was written; run again without --resume");
    inputs = &member(j, "inputs", "");
    if (!inputs->is_object()) throw Error(fmt::format("must be an object, got {}", kind(*inputs)), "/inputs");
  });
  for (const auto& input : fingerprint.inputs) {
    const auto it = inputs->find(input.name);
    if (it == inputs->end())
      throw Error(fmt::format("the scene reads this file, which checkpoint {} does not list; run again without --resume", file),
                  input.path.string());
    if (*it != input.fingerprint)
      throw Error(fmt::format("changed since checkpoint {} was written; run again without --resume", file),
                  input.path.string());
  }
  Checkpoint c;
  in_checkpoint([&] {
    const long long frame = integer(member(j, "frame", ""), 1, kMaxFrames, "/frame");
    if (frame > frames_requested)
      throw Error(fmt::format("the checkpoint is at frame {}, past the {} frame(s) this run asks for (--frames or the "
                              "scene's frames)",
                              frame, frames_requested),
                  "/frame");
    c.frame = static_cast<int>(frame);
    c.state.x = read_vector(j, "x", dofs);
    if (integrator.dynamic()) c.state.v = read_vector(j, "v", dofs);
    c.integrator_state = member(j, "integrator_state", "");
    if (!c.integrator_state.is_object())
      throw Error(fmt::format("must be an object, got {}", kind(c.integrator_state)), "/integrator_state");
  });
  return c;
}

void restore_integrator(Integrator& integrator, const Checkpoint& checkpoint, const fs::path& out) {
  const std::string where = (out / "checkpoint.json").string() + ": /integrator_state";
  try {
    integrator.restore_state(checkpoint.integrator_state, checkpoint.frame);
  } catch (const Error& e) {
    // A JSON path inside the state continues the state's own.
    if (e.context().rfind('/', 0) == 0) throw Error(e.message(), where + e.context());
    throw e.within(where);
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("malformed: {}", e.what()), where);
  }
}

}  // namespace sinew
