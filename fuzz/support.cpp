#include "support.hpp"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <unistd.h>

#include "sinew/core/error.hpp"
#include "sinew/io/mesh_reader.hpp"
#include "sinew/io/surface_reader.hpp"

namespace sinew::fuzz {
namespace {

const std::filesystem::path& folder() {
  static const std::filesystem::path dir = [] {
    const char* base = std::getenv("TMPDIR");
    auto d = std::filesystem::path(base && *base ? base : "/tmp") / ("sinew-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "sinew fuzz finding: %s\n", what.c_str());
  std::abort();
}

}  // namespace

std::filesystem::path write_input(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const auto path = folder() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

std::filesystem::path write_input(const std::string& text, const std::string& name) {
  return write_input(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(), name);
}

void expect_clean(const std::function<void()>& read, const std::filesystem::path& file) {
  expect_clean(read, std::vector<std::filesystem::path>{file});
}

void expect_clean(const std::function<void()>& read, const std::vector<std::filesystem::path>& files) {
  try {
    read();
  } catch (const Error& e) {
    const std::string text = e.what();
    bool named = false;
    std::string names;
    for (const auto& file : files) {
      named = named || text.find(file.filename().string()) != std::string::npos;
      names += (names.empty() ? "" : " or ") + file.filename().string();
    }
    if (!named) finding("an error that does not name the input file " + names + ": " + text);
  } catch (const std::exception& e) {
    finding(std::string("an exception other than sinew::Error: ") + e.what());
  } catch (...) {
    finding("a thrown value that is not an exception");
  }
}

void fuzz_volume_mesh(const std::uint8_t* data, std::size_t size, const std::string& extension) {
  const auto path = write_input(data, size, "input" + extension);
  expect_clean([&] { read_volume_mesh(path); }, path);
}

void fuzz_surface(const std::uint8_t* data, std::size_t size, const std::string& extension) {
  const auto path = write_input(data, size, "input" + extension);
  expect_clean([&] { read_triangle_surface(path, /*require_closed=*/size % 2 == 0); }, path);
}

}  // namespace sinew::fuzz
