// Texture loading: a good PNG, a missing file, a corrupt file.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>
#include <stb/stb_image_write.h>

#include "scene/asset_error.h"
#include "scene/textures.h"

namespace {

namespace fs = std::filesystem;

// A fresh folder under the system temp dir, removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            (std::string("rolypoly_scene_") + info->name() + "_" + std::to_string(::getpid()));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

TEST(Textures, LoadsRgbPngAsRgba8TopRowFirst) {
  TempDir dir;
  // 3 x 2 RGB image, rows top to bottom.
  const unsigned char rgb[] = {255, 0, 0,   0, 255, 0,   0, 0, 255,
                               10, 20, 30,  40, 50, 60,  70, 80, 90};
  const std::string path = dir.file("small.png");
  ASSERT_NE(stbi_write_png(path.c_str(), 3, 2, 3, rgb, 3 * 3), 0);
  const rp::scene::Texture t = rp::scene::load_texture(path, "small");
  EXPECT_EQ(t.name, "small");
  EXPECT_EQ(t.width, 3);
  EXPECT_EQ(t.height, 2);
  ASSERT_EQ(t.rgba.size(), 3u * 2u * 4u);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(t.rgba[i * 4 + 0], rgb[i * 3 + 0]);
    EXPECT_EQ(t.rgba[i * 4 + 1], rgb[i * 3 + 1]);
    EXPECT_EQ(t.rgba[i * 4 + 2], rgb[i * 3 + 2]);
    EXPECT_EQ(t.rgba[i * 4 + 3], 255);  // opaque
  }
}

TEST(Textures, MissingFileThrowsAssetErrorNamingThePath) {
  TempDir dir;
  const std::string path = dir.file("does_not_exist.png");
  try {
    rp::scene::load_texture(path, "nothing");
    FAIL() << "no exception";
  } catch (const rp::scene::AssetError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    // the system's reason (stb_image only knew "can't fopen")
    EXPECT_NE(message.find("No such file or directory"), std::string::npos) << message;
  }
}

TEST(Textures, CorruptFileThrowsAssetErrorWithStbReason) {
  TempDir dir;
  const std::string path = dir.file("garbage.png");
  {
    std::ofstream out(path, std::ios::binary);
    out << "this is not a PNG file, just some bytes \x01\x02\x03\x04";
  }
  try {
    rp::scene::load_texture(path, "garbage");
    FAIL() << "no exception";
  } catch (const rp::scene::AssetError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    // "...: <reason>" with a non-empty reason after the path.
    const size_t colon = message.rfind(": ");
    ASSERT_NE(colon, std::string::npos);
    EXPECT_GT(message.size(), colon + 2) << message;
  }
  // AssetError is a std::runtime_error, so generic handlers catch it too.
  EXPECT_THROW(rp::scene::load_texture(path, "garbage"), std::runtime_error);
}

TEST(Textures, TruncatedPngThrows) {
  TempDir dir;
  const unsigned char rgb[4 * 4 * 3] = {};
  const std::string good = dir.file("good.png"), cut = dir.file("cut.png");
  ASSERT_NE(stbi_write_png(good.c_str(), 4, 4, 3, rgb, 4 * 3), 0);
  std::ifstream in(good, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 40u);
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, 40);  // signature + part of IHDR
  EXPECT_THROW(rp::scene::load_texture(cut, "cut"), rp::scene::AssetError);
}

}  // namespace
