// truth/exr_io.h: the OpenEXR files of `render --quality pathtraced` and `render --exr`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/cli_runner.h"
#include "truth/exr_io.h"

namespace rp::test {
namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(no exception)";
}

TEST(ExrIo, TwoLayersRoundTripBitExact) {
  TempDir dir;
  const uint32_t w = 5, h = 3;  // not square: rows and columns cannot be swapped unnoticed
  std::vector<float> combined(w * h * 3), albedo(w * h * 3);
  for (size_t i = 0; i < combined.size(); ++i) {
    combined[i] = float(i) * 1.25e-3f + 1e-38f * float(i % 7);  // denormals and normals
    albedo[i] = -float(i) / 7.0f;
  }
  // Values a lossy path would change: tiny, huge, negative zero, infinity, a NaN.
  combined[0] = std::numeric_limits<float>::denorm_min();
  combined[1] = 3.0e38f;
  combined[2] = -0.0f;
  albedo[3] = std::numeric_limits<float>::infinity();
  albedo[4] = std::numeric_limits<float>::quiet_NaN();
  const std::filesystem::path path = dir / "frame.exr";
  rp::truth::write_exr_atomic(path, w, h, {{"", &combined}, {"albedo", &albedo}});
  EXPECT_EQ(files_with_suffix(dir.path(), ""), std::vector<std::string>{"frame.exr"})
      << "no temporary file remains";

  for (const auto& [name, expected] :
       {std::pair<std::string, const std::vector<float>*>{"", &combined}, {"albedo", &albedo}}) {
    uint32_t rw = 0, rh = 0;
    const std::vector<float> read = rp::truth::read_exr_layer(path, name, rw, rh);
    EXPECT_EQ(rw, w);
    EXPECT_EQ(rh, h);
    ASSERT_EQ(read.size(), expected->size()) << name;
    EXPECT_EQ(std::memcmp(read.data(), expected->data(), read.size() * sizeof(float)), 0)
        << "layer '" << name << "' is not bit-exact";
  }
}

TEST(ExrIo, MissingLayerOrFileIsNamed) {
  TempDir dir;
  const std::vector<float> rgb(2 * 2 * 3, 0.5f);
  const std::filesystem::path path = dir / "a.exr";
  rp::truth::write_exr_atomic(path, 2, 2, {{"", &rgb}, {"direct", &rgb}});
  uint32_t w = 0, h = 0;
  const std::string missing =
      error_of([&] { rp::truth::read_exr_layer(path, "indirect", w, h); });
  EXPECT_NE(missing.find(path.string()), std::string::npos) << missing;
  EXPECT_NE(missing.find("'indirect'"), std::string::npos) << missing;
  EXPECT_NE(missing.find("'direct'"), std::string::npos) << "lists what the file has: " << missing;

  const std::string no_file =
      error_of([&] { rp::truth::read_exr_layer(dir / "none.exr", "", w, h); });
  EXPECT_NE(no_file.find("cannot read EXR " + (dir / "none.exr").string()), std::string::npos)
      << no_file;
}

TEST(ExrIo, UnwritableFolderThrowsAndLeavesNoFile) {
  TempDir dir;
  const std::vector<float> rgb(4 * 4 * 3, 1.0f);
  const std::filesystem::path path = dir / "missing" / "frame.exr";
  const std::string error = error_of([&] { rp::truth::write_exr_atomic(path, 4, 4, {{"", &rgb}}); });
  EXPECT_EQ(error.rfind("cannot write EXR " + path.string() + ": ", 0), 0u) << error;
  EXPECT_FALSE(std::filesystem::exists(dir / "missing"));
  EXPECT_TRUE(files_with_suffix(dir.path(), "").empty());
}

TEST(ExrIo, MismatchedLayersAreRejectedBeforeWriting) {
  TempDir dir;
  const std::vector<float> small(3, 0.0f), rgb(2 * 2 * 3, 0.0f);
  const std::filesystem::path path = dir / "x.exr";
  EXPECT_NE(error_of([&] { rp::truth::write_exr_atomic(path, 2, 2, {{"", &small}}); })
                .find("does not hold 2x2 RGB pixels"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              rp::truth::write_exr_atomic(path, 2, 2, {{"a", &rgb}, {"a", &rgb}});
            }).find("twice"),
            std::string::npos);
  EXPECT_TRUE(files_with_suffix(dir.path(), "").empty());
}

}  // namespace
}  // namespace rp::test
