#pragma once
// Shared pieces of the libFuzzer targets (docs/hardening.md). Sinew's readers take paths, so
// each input is written to a file in a per-process temporary folder first. What counts as a
// finding, beyond the crashes, leaks and undefined behaviour the sanitizers catch:
//   - any exception other than sinew::Error (std::bad_alloc, nlohmann's, std::out_of_range):
//     the CLI would print "internal error" naming no file;
//   - a sinew::Error whose text does not name the input file.
// Either aborts, so libFuzzer saves the input as a crash.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace sinew::fuzz {

// Writes the input to <temp folder>/<name> and returns that path.
std::filesystem::path write_input(const std::uint8_t* data, std::size_t size, const std::string& name);
std::filesystem::path write_input(const std::string& text, const std::string& name);

// Runs `read`; a sinew::Error must name `file` (its file name is enough), anything else aborts.
void expect_clean(const std::function<void()>& read, const std::filesystem::path& file);
// The same for a reader of several files: its error must name one of them.
void expect_clean(const std::function<void()>& read, const std::vector<std::filesystem::path>& files);

// read_volume_mesh on the input saved with the given extension (".vtk", ".vtu", ...).
void fuzz_volume_mesh(const std::uint8_t* data, std::size_t size, const std::string& extension);
// read_triangle_surface on the input saved with the given extension (".obj", ".stl", ...).
void fuzz_surface(const std::uint8_t* data, std::size_t size, const std::string& extension);

}  // namespace sinew::fuzz
