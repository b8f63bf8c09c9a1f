// Inputs the fuzz targets found problems with (tests/data/fuzz/<target>/, docs/hardening.md),
// read back on every test run the way the target reads them: each must end in success or in a
// sinew::Error that names the file - never a crash, another exception or an unnamed error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>

#include "io_test_support.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/io/surface_reader.hpp"
#include "sinew/material/expression.hpp"
#include "sinew/model/rig_reader.hpp"
#include "sinew/model/model.hpp"
#include "sinew/model/scene.hpp"
#include "sinew/run/checkpoint.hpp"
#include "sinew/run/frame_log.hpp"

namespace sinew {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) { return test::read_file(p); }

// Copies the finding to `dir/name` (the readers choose by extension) and reads it.
using Reader = std::function<void(const fs::path& input, const test::TempDir& dir)>;

Reader as(const std::string& name, std::function<void(const fs::path&)> read) {
  return [name, read](const fs::path& input, const test::TempDir& dir) {
    const fs::path file = dir.write(name, slurp(input));
    try {
      read(file);
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << input << ": the error names no file: " << e.what();
    }
  };
}

// fuzz_checkpoint's scene, built once: the findings are its checkpoints, damaged.
struct Resumable {
  Resumable()
      : scene(load_scene(test::data_path("checkpoint_scene/scene.json"))),
        model(build_model(scene)),
        fingerprint(fingerprint_run(scene)) {}
  Scene scene;
  Model model;
  RunFingerprint fingerprint;
};

std::map<std::string, Reader> readers() {
  const auto mesh = [](const fs::path& p) { read_volume_mesh(p); };
  const auto surface = [](const fs::path& p) { read_triangle_surface(p, false); };
  return {
      {"fuzz_scene", as("scene.json", [](const fs::path& p) { load_scene(p); })},
      {"fuzz_rig", as("rig.json", [](const fs::path& p) { load_rig(p); })},
      {"fuzz_mesh_vtk", as("input.vtk", mesh)},
      {"fuzz_mesh_vtu", as("input.vtu", mesh)},
      {"fuzz_mesh_gmsh", as("input.msh", mesh)},
      {"fuzz_mesh_medit", as("input.mesh", mesh)},
      {"fuzz_surface_obj", as("input.obj", surface)},
      {"fuzz_surface_off", as("input.off", surface)},
      {"fuzz_surface_ply", as("input.ply", surface)},
      {"fuzz_surface_stl", as("input.stl", surface)},
      {"fuzz_mesh_tetgen",
       [](const fs::path& input, const test::TempDir& dir) {
         const std::string text = slurp(input);
         const std::size_t split = text.find("\n---\n");
         dir.write("input.node", split == std::string::npos ? text : text.substr(0, split + 1));
         dir.write("input.ele", split == std::string::npos ? std::string() : text.substr(split + 5));
         try {
           read_volume_mesh(dir / "input.node");
         } catch (const Error& e) {
           EXPECT_NE(std::string(e.what()).find("input."), std::string::npos) << input << ": " << e.what();
         }
       }},
      {"fuzz_checkpoint",
       [](const fs::path& input, const test::TempDir& dir) {
         // The checkpoint, then after a line ---frames.jsonl--- the frame records (fuzz_checkpoint.cpp).
         static Resumable r;
         const std::string text = slurp(input), separator = "\n---frames.jsonl---\n";
         const std::size_t split = text.find(separator);
         dir.write("checkpoint.json", text.substr(0, split));
         dir.write("frames.jsonl", split == std::string::npos ? std::string() : text.substr(split + separator.size()));
         try {
           const Checkpoint c = read_checkpoint(dir.path(), r.fingerprint, *r.model.integrator, r.model.initial.x.size(),
                                                r.scene.frames);
           read_frame_log(dir.path(), c.frame);
           restore_integrator(*r.model.integrator, c, dir.path());
         } catch (const Error& e) {
           const std::string message = e.what();
           EXPECT_TRUE(message.find("checkpoint.json") != std::string::npos ||
                       message.find("frames.jsonl") != std::string::npos)
               << input << ": the error names no file: " << message;
         }
       }},
      {"fuzz_expression",
       [](const fs::path& input, const test::TempDir&) {
         try {
           ScalarFunction::parse(slurp(input), {{"a", 2.0}, {"mu", 1e5}, {"k", -3.5}}).derivatives(1.0);
         } catch (const Error&) {
         }
       }},
  };
}

TEST(FuzzRegression, EveryFindingIsReadCleanly) {
  const fs::path root = test::data_path("fuzz");
  const auto known = readers();
  int inputs = 0;
  for (const auto& target : fs::directory_iterator(root)) {
    if (!target.is_directory()) continue;
    const auto reader = known.find(target.path().filename().string());
    ASSERT_NE(reader, known.end()) << "no reader for " << target.path();
    for (const auto& input : fs::directory_iterator(target.path())) {
      SCOPED_TRACE(input.path().string());
      test::TempDir dir;
      reader->second(input.path(), dir);  // another exception escapes and fails the test
      ++inputs;
    }
  }
  RecordProperty("inputs", inputs);
}

}  // namespace
}  // namespace sinew
