// PNG and JSON output: whole files or nothing, the documented bench schema.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "app/png_output.h"
#include "support/cli_runner.h"
#include "support/image_metrics.h"

namespace rp::app {
namespace {

TEST(PngOutput, FrameNamesAreNumberedWithFourDigits) {
  EXPECT_EQ(frame_file_name(0), "frame_0000.png");
  EXPECT_EQ(frame_file_name(42), "frame_0042.png");
  EXPECT_EQ(frame_file_name(12345), "frame_12345.png");
}

TEST(PngOutput, WritesTheImageAndNoTemporaryFile) {
  rp::test::TempDir dir;
  // 3x2 image with distinct pixels, so row order and channel order are both checked.
  std::vector<uint8_t> rgba;
  for (int i = 0; i < 6; ++i)
    rgba.insert(rgba.end(), {uint8_t(10 * i), uint8_t(100 + i), uint8_t(250 - i), 255});
  write_png_atomic(dir / "a.png", 3, 2, rgba);
  rp::test::Rgba8Image back = rp::test::load_png((dir / "a.png").string());
  EXPECT_EQ(back.width, 3);
  EXPECT_EQ(back.height, 2);
  EXPECT_EQ(back.rgba, rgba);
  int entries = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    (void)e;
    ++entries;
  }
  EXPECT_EQ(entries, 1) << "only a.png may remain";
}

TEST(PngOutput, FailureNamesTheFileAndLeavesNothing) {
  rp::test::TempDir dir;
  std::vector<uint8_t> rgba(4 * 4, 128);
  std::filesystem::path target = dir / "missing_folder" / "b.png";
  try {
    write_png_atomic(target, 2, 2, rgba);
    FAIL() << "writing into a missing folder must throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("b.png"), std::string::npos) << e.what();
  }
  EXPECT_THROW(write_png_atomic(dir / "c.png", 3, 2, rgba), std::runtime_error);  // size mismatch
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(PngOutput, EnsureDirectoryCreatesParentsAndRejectsFiles) {
  rp::test::TempDir dir;
  ensure_directory(dir / "x" / "y");
  EXPECT_TRUE(std::filesystem::is_directory(dir / "x" / "y"));
  std::ofstream(dir / "file") << "not a folder";
  EXPECT_THROW(ensure_directory(dir / "file"), std::runtime_error);
}

TEST(BenchReport, WriteTextAtomicReplacesWholeFile) {
  rp::test::TempDir dir;
  write_text_atomic(dir / "r.json", "first version, longer\n");
  write_text_atomic(dir / "r.json", "{}\n");
  std::ifstream in(dir / "r.json");
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(content, "{}\n");
  EXPECT_EQ(rp::test::files_with_suffix(dir.path(), "").size(), 1u);
}

}  // namespace
}  // namespace rp::app
