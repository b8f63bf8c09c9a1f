// Every example scene has a picture in the docs, made by scripts/render_docs_images.py: each
// examples/NAME.json is shown as docs/img/example_NAME.png somewhere in README.md or docs/, and
// each examples/features/NAME.json as docs/img/feature_NAME.png right under its scene in
// docs/scene-format.md. A new example without its picture fails here (run the script).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io_test_support.hpp"

namespace sinew {
namespace {

const std::filesystem::path kRoot = test::data_path("../..");

bool is_png(const std::filesystem::path& path) { return test::read_file(path).rfind("\x89PNG\r\n\x1a\n", 0) == 0; }

TEST(DocsPictures, EveryExampleIsPicturedInTheDocs) {
  std::string docs = test::read_file(kRoot / "README.md");
  for (const auto& entry : std::filesystem::directory_iterator(kRoot / "docs"))
    if (entry.path().extension() == ".md") docs += test::read_file(entry.path());
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kRoot / "examples")) {
    if (entry.path().extension() != ".json") continue;
    const std::string picture = "img/example_" + entry.path().stem().string() + ".png";
    SCOPED_TRACE(picture);
    EXPECT_TRUE(is_png(kRoot / "docs" / picture)) << "missing; run scripts/render_docs_images.py";
    EXPECT_NE(docs.find(picture + ")"), std::string::npos) << "no doc shows it";
    ++count;
  }
  EXPECT_GE(count, 10);
}

TEST(DocsPictures, EveryFeatureSceneIsPicturedUnderItsScene) {
  const std::string doc = test::read_file(kRoot / "docs" / "scene-format.md");
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kRoot / "examples" / "features")) {
    if (entry.path().extension() != ".json") continue;
    const std::string name = entry.path().stem().string();
    SCOPED_TRACE(name);
    EXPECT_TRUE(is_png(kRoot / "docs" / "img" / ("feature_" + name + ".png"))) << "missing; run scripts/render_docs_images.py";
    // The scene's block, then (before the next scene's marker) its picture.
    const auto at = doc.find("<!-- examples/features/" + name + ".json -->");
    ASSERT_NE(at, std::string::npos);
    const auto next = doc.find("<!-- examples/features/", at + 1);
    const auto picture = doc.find("(img/feature_" + name + ".png)", at);
    EXPECT_TRUE(picture != std::string::npos && picture < next) << "not shown under its scene";
    ++count;
  }
  EXPECT_GE(count, 20);
}

}  // namespace
}  // namespace sinew
