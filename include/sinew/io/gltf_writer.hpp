#pragma once
// Animated glTF 2.0 binary (.glb) of triangle meshes whose vertices move from frame to frame:
// frame 0 is the base POSITION, every later frame a morph target (POSITION displacement from
// frame 0), and one animation steps the morph weights so frame f shows exactly target f
// (STEP interpolation: no blend between frames). glTF viewers (three.js, Blender, Babylon)
// play it as it is. Per-vertex scalar fields travel as float accessors listed under the
// mesh's extras (glTF has no per-frame vertex attribute), with COLOR_0 holding frame 0 of the
// first field so plain viewers show colour too.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace sinew {

struct AnimatedMesh {
  std::string name;
  std::string role;                 // free text for the reader ("body", "obstacle", ...), in extras
  Eigen::MatrixX3i triangles;       // 0-based, counter-clockwise seen from outside
  std::vector<Eigen::MatrixX3f> positions;  // per frame, one row per vertex
  std::vector<std::string> field_names;     // per-vertex scalars, the same for every frame
  std::vector<std::vector<Eigen::VectorXf>> fields;  // [frame][field], one value per vertex
  Eigen::Vector4f color{0.8f, 0.8f, 0.8f, 1.0f};     // base colour (linear RGBA); alpha < 1 blends
};

struct AnimatedScene {
  std::vector<int> frame_numbers;  // the simulation's frame numbers, one per stored frame
  std::vector<double> times;       // animation time of each frame in seconds, strictly increasing
  std::vector<AnimatedMesh> meshes;
  // Sinew's scenes are z-up; glTF is y-up. With z_up the meshes hang under a root node that
  // turns +z into +y, so the data stay in the simulation's coordinates.
  bool z_up = true;
  std::string generator = "Sinew";
};

// The .glb bytes. Throws sinew::Error (naming the mesh and frame) on inconsistent sizes, an
// index out of range, non-finite values, an empty scene, or times that do not increase.
std::string glb_bytes(const AnimatedScene& scene);

// glb_bytes written through write_file_atomically.
void write_glb(const std::filesystem::path& path, const AnimatedScene& scene);

}  // namespace sinew
