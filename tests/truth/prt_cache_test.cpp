// The PRT disk cache (src/truth/prt_cache.h): an entry reads back bit-identical, a changed
// setting, mesh, material or instance is another key, the thread count is not, and a truncated
// or corrupt file is refused and rebuilt.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>

#include "prt_test_scenes.h"
#include "truth/prt_cache.h"

namespace rp::truth {
namespace {

using namespace prt_test;
namespace fs = std::filesystem;

// A fresh folder per test under the test temp dir, removed afterwards.
class PrtCache : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> serial{0};
    dir_ = fs::path(::testing::TempDir()) /
           ("rolypoly-prt-cache-" + std::to_string(::getpid()) + "-" + std::to_string(serial++));
    fs::remove_all(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

scene::SceneAssets box_assets() {
  return one_mesh_assets(glm::vec3(0.9f, 0.6f, 0.3f), [](scene::Mesh& m) { open_box(m, 3); });
}

PrtSettings interreflected() {
  PrtSettings s;
  s.kind = PrtKind::kInterreflected;
  s.bands = 5;
  s.samples = 64;
  s.bounces = 2;
  s.sun_directions = {{0.3f, 1.0f, 0.2f}};  // one directional light's bounce traced too
  s.glow_cells = {{{-0.2f, 0.8f, 0.3f}, {2.0f, 1.5f, 1.0f}}};  // and a glow cell's light
  return s;
}

void expect_same(const PrtTransfer& a, const PrtTransfer& b) {
  EXPECT_EQ(a.bands, b.bands);
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.bounces, b.bounces);
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_EQ(a.channels, b.channels);
  ASSERT_EQ(a.instances.size(), b.instances.size());
  for (size_t i = 0; i < a.instances.size(); ++i) {
    EXPECT_EQ(a.instances[i].first, b.instances[i].first);
    EXPECT_EQ(a.instances[i].count, b.instances[i].count);
  }
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.coefficients, b.coefficients);  // bit for bit (no NaN here)
  EXPECT_EQ(a.shadowed, b.shadowed);
  EXPECT_EQ(a.sun_directions, b.sun_directions);
  EXPECT_EQ(a.sun_bounce, b.sun_bounce);
  EXPECT_EQ(a.glow_cells, b.glow_cells);
  EXPECT_EQ(a.glow, b.glow);
}

TEST_F(PrtCache, RoundTripIsIdentical) {
  const auto assets = box_assets();
  const auto frame = one_instance_frame();
  const CachedPrt first = cached_prt_transfer(assets, frame, interreflected(), dir_);
  EXPECT_FALSE(first.from_cache);
  EXPECT_EQ(first.transfer.shadowed.size(), size_t(first.transfer.vertex_count()) * 25);
  EXPECT_EQ(first.transfer.sun_bounce.size(), size_t(first.transfer.vertex_count()) * 3);
  EXPECT_EQ(first.transfer.glow.size(), size_t(first.transfer.vertex_count()) * 3);
  ASSERT_TRUE(fs::exists(first.file));
  EXPECT_EQ(first.file.parent_path(), dir_);
  const CachedPrt second = cached_prt_transfer(assets, frame, interreflected(), dir_);
  EXPECT_TRUE(second.from_cache);
  EXPECT_EQ(second.file, first.file);
  expect_same(first.transfer, second.transfer);
  expect_same(first.transfer, compute_prt_transfer(assets, frame, interreflected()));
}

TEST_F(PrtCache, ChangedSettingOrSceneMisses) {
  const auto assets = box_assets();
  const auto frame = one_instance_frame();
  const PrtSettings base = interreflected();
  const std::string key = prt_key(assets, frame, base);
  EXPECT_EQ(key.size(), 16u);
  PrtSettings s = base;
  s.threads = 3;  // the result does not depend on it
  EXPECT_EQ(prt_key(assets, frame, s), key);
  for (int change = 0; change < 8; ++change) {
    s = base;
    if (change == 0) s.bands = 3;
    if (change == 1) s.kind = PrtKind::kShadowed;
    if (change == 2) s.bounces = 3;
    if (change == 3) s.samples = 128;
    if (change == 4) s.sun_directions[0].x = 0.31f;
    if (change == 5) s.sun_directions.clear();
    if (change == 6) s.glow_cells[0].irradiance.y = 1.25f;
    if (change == 7) s.glow_cells.clear();
    EXPECT_NE(prt_key(assets, frame, s), key) << "change " << change;
  }
  // Bounces and suns are no part of a shadowed transfer's key, samples and glow of an
  // unshadowed one's; a sun's direction counts, not its length.
  PrtSettings a = base, b = base;
  b.sun_directions[0] *= 2.0f;
  EXPECT_EQ(prt_key(assets, frame, a), prt_key(assets, frame, b));
  a.kind = b.kind = PrtKind::kShadowed;
  b.bounces = 7;
  b.sun_directions.clear();
  EXPECT_EQ(prt_key(assets, frame, a), prt_key(assets, frame, b));
  a.kind = b.kind = PrtKind::kUnshadowed;
  b.samples = 7;
  b.glow_cells.clear();
  EXPECT_EQ(prt_key(assets, frame, a), prt_key(assets, frame, b));

  scene::SceneAssets recoloured = assets;
  recoloured.materials[0].albedo.x = 0.5f;
  EXPECT_NE(prt_key(recoloured, frame, base), key);
  scene::SceneAssets bent = assets;
  bent.meshes[0].vertices[3].position.y += 0.01f;
  EXPECT_NE(prt_key(bent, frame, base), key);
  scene::FrameScene moved = frame;
  moved.instances[0].model = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0.5f, 0));
  EXPECT_NE(prt_key(assets, moved, base), key);
  // Lighting and camera are no part of it.
  scene::FrameScene lit = frame;
  lit.camera.position.x += 1.0f;
  lit.light.intensity *= 2.0f;
  EXPECT_EQ(prt_key(assets, lit, base), key);

  // A changed setting computes and stores a second entry beside the first.
  const CachedPrt first = cached_prt_transfer(assets, frame, base, dir_);
  s = base;
  s.samples = 32;
  const CachedPrt other = cached_prt_transfer(assets, frame, s, dir_);
  EXPECT_FALSE(other.from_cache);
  EXPECT_NE(other.file, first.file);
  EXPECT_EQ(other.transfer.samples, 32u);
  EXPECT_TRUE(cached_prt_transfer(assets, frame, base, dir_).from_cache);
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void spit(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
}

TEST_F(PrtCache, TruncatedOrCorruptFileIsRejectedAndRebuilt) {
  const auto assets = box_assets();
  const auto frame = one_instance_frame();
  const PrtSettings s = interreflected();
  const std::string key = prt_key(assets, frame, s);
  const CachedPrt made = cached_prt_transfer(assets, frame, s, dir_);
  const std::string good = slurp(made.file);
  ASSERT_TRUE(read_prt_file(made.file, key, s).has_value());

  for (size_t keep : {size_t(0), size_t(5), size_t(40), good.size() / 2, good.size() - 1}) {
    spit(made.file, good.substr(0, keep));
    EXPECT_FALSE(read_prt_file(made.file, key, s).has_value()) << "truncated to " << keep;
  }
  std::string flipped = good;
  flipped[flipped.size() / 2] = char(flipped[flipped.size() / 2] ^ 0x10);  // a coefficient bit
  spit(made.file, flipped);
  EXPECT_FALSE(read_prt_file(made.file, key, s).has_value()) << "corrupt";
  spit(made.file, good + "x");
  EXPECT_FALSE(read_prt_file(made.file, key, s).has_value()) << "trailing byte";

  // The right bytes under another key or other settings are refused too.
  spit(made.file, good);
  EXPECT_FALSE(read_prt_file(made.file, std::string(16, '0'), s).has_value());
  PrtSettings other = s;
  other.bounces = 5;
  EXPECT_FALSE(read_prt_file(made.file, key, other).has_value());
  EXPECT_FALSE(read_prt_file(dir_ / "missing.bin", key, s).has_value());

  // A corrupt entry is computed anew and replaced by a good one.
  spit(made.file, good.substr(0, good.size() / 3));
  const CachedPrt rebuilt = cached_prt_transfer(assets, frame, s, dir_);
  EXPECT_FALSE(rebuilt.from_cache);
  expect_same(rebuilt.transfer, made.transfer);
  EXPECT_EQ(slurp(made.file), good);
  EXPECT_TRUE(cached_prt_transfer(assets, frame, s, dir_).from_cache);
}

TEST(PrtCacheDir, FollowsTheTruthCacheRoot) {
  const char* old = std::getenv("XDG_CACHE_HOME");
  const std::string saved = old ? old : "";
  ::setenv("XDG_CACHE_HOME", "/tmp/xdg-test", 1);
  EXPECT_EQ(default_prt_cache_dir(), fs::path("/tmp/xdg-test/rolypoly/prt"));
  if (old)
    ::setenv("XDG_CACHE_HOME", saved.c_str(), 1);
  else
    ::unsetenv("XDG_CACHE_HOME");
}

}  // namespace
}  // namespace rp::truth
