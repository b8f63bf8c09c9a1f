#pragma once
// A self-contained browser viewer of a run: an animated glTF binary (gltf_writer.hpp) and an
// HTML page that shows it with three.js (play/pause, frame slider, field selection, colour
// bar). The page carries the GLB (base64) and the bundled viewer script inline, so it opens
// from the disk with no network and no web server. The script is built from viewer/ (three.js
// from npm, bundled by esbuild) into the build folder.
//
// Frames are fed one at a time as the run produces them; finish() writes both files
// atomically. All frames are kept in memory (as 32-bit floats) until then.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "sinew/io/gltf_writer.hpp"

namespace sinew {

enum class ViewerRole { Body, RenderSurface, Obstacle, Bone };
const char* to_string(ViewerRole role);

// One object shown in the viewer; its topology is fixed, its vertices move per frame.
struct ViewerObject {
  std::string name;  // unique
  ViewerRole role = ViewerRole::Body;
  Eigen::MatrixX3i triangles;            // 0-based
  std::vector<std::string> field_names;  // per-vertex scalars given every frame (may be empty)
};

// What one object looks like in one frame.
struct ViewerObjectFrame {
  Eigen::MatrixX3d positions;          // one row per vertex
  std::vector<Eigen::VectorXd> fields;  // in the order of ViewerObject::field_names
};

struct ViewerOptions {
  std::string title = "Sinew";
  bool z_up = true;  // the scene's up axis is +z (else +y)
  double frames_per_second = 12.0;  // playback speed of the page
  // The bundled viewer script; default: the build's viewer/sinew_viewer.js, or the file named
  // by the environment variable SINEW_VIEWER_SCRIPT.
  std::filesystem::path script;
};

// The default viewer script (see ViewerOptions::script).
std::filesystem::path default_viewer_script();

class ViewerWriter {
 public:
  // Throws sinew::Error on no objects, a repeated or empty name, or an object without triangles.
  ViewerWriter(std::vector<ViewerObject> objects, ViewerOptions options = {});

  // Frame `frame` (the simulation's number) at animation time `time` (seconds; must increase):
  // one entry per object, in construction order. Throws sinew::Error naming the object on a
  // vertex or field count that does not match, or non-finite values.
  void add_frame(int frame, double time, const std::vector<ViewerObjectFrame>& objects);
  std::size_t frames() const { return scene_.frame_numbers.size(); }

  // Writes `html` and, beside it, the GLB with the same stem (viewer.html + viewer.glb). Both
  // atomically; a missing viewer script is a sinew::Error naming it (and nothing is written).
  void finish(const std::filesystem::path& html) const;

  const AnimatedScene& scene() const { return scene_; }

 private:
  std::vector<ViewerObject> objects_;
  ViewerOptions options_;
  AnimatedScene scene_;
};

// The page alone: `glb` embedded, `script` (the bundled viewer's text) inline.
std::string viewer_html(const std::string& glb, const std::string& script, const ViewerOptions& options);

}  // namespace sinew
