// The atrium (scene/atrium.h): what it holds (its size and kind, materials whose textures exist,
// the light types, finite geometry) and that its generator writes the same bytes every run,
// pinned by a hash that changes only when the atrium is changed on purpose (then bump
// scene::kAtriumVersion, which names the cached file, and the hash here together).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "io/fnv1a.h"
#include "scene/atrium.h"
#include "scene/gltf_loader.h"

namespace rp::scene {
namespace {

// FNV-1a (64 bits) of the GLB `gen_load_scene OUT --atrium` writes, on the project's
// toolchain: x86-64, GCC without -march (no fused multiply-adds), glibc's std::sin and
// std::cos (lathes, arches, some texture patterns), stb's PNG writer.
constexpr uint64_t kAtriumGlbHash = 0x37e27319800b09b4ull;

const Atrium& atrium() {
  static const Atrium a = make_atrium();
  return a;
}

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

uint64_t fnv1a(const std::string& bytes) {
  io::Fnv1a h;
  h.bytes(bytes.data(), bytes.size());
  return h.get();
}

class ScratchDir {
 public:
  ScratchDir()
      : path_(std::filesystem::temp_directory_path() /
              ("rolypoly_atrium_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

void generate(const std::filesystem::path& file) {
  const std::string command =
      std::string(ROLYPOLY_GEN_LOAD_SCENE) + " '" + file.string() + "' --atrium > /dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
}

TEST(Atrium, HasTheSizeAndKindOfAnArchitecturalScene) {
  const Atrium& a = atrium();
  size_t triangles = 0;
  for (const MeshInstance& inst : a.frame.instances) {
    ASSERT_LT(inst.mesh, a.assets.meshes.size());
    triangles += a.assets.meshes[inst.mesh].triangles.size();
  }
  EXPECT_GE(triangles, 200000u);
  EXPECT_LE(triangles, 300000u);
  EXPECT_GE(a.assets.textures.size(), 30u);
  EXPECT_LE(a.assets.textures.size(), 50u);
  std::set<LightType> types;
  for (const PunctualLight& l : a.frame.lights) types.insert(l.type);
  EXPECT_EQ(types.size(), 3u) << "a sun, point lights and spot lights";
  EXPECT_LE(a.frame.lights.size(), 8u) << "the real-time passes draw 8 punctual lights";
  EXPECT_FALSE(a.frame.lamp);
  bool masked_double_sided = false, metal = false;
  for (const Material& m : a.assets.materials) {
    masked_double_sided |= m.alpha_mode == AlphaMode::kMask && m.double_sided;
    metal |= m.specular.metal;
  }
  EXPECT_TRUE(masked_double_sided) << "leaves are alpha-masked, double-sided cards";
  EXPECT_TRUE(metal) << "lamps and railings are metal";
}

TEST(Atrium, EveryMaterialsTexturesExist) {
  const Atrium& a = atrium();
  const int n = int(a.assets.textures.size());
  std::set<int> used;
  for (const Material& m : a.assets.materials)
    for (int t : {m.texture, m.metallic_roughness_texture, m.normal_texture, m.emission_texture}) {
      EXPECT_GE(t, -1) << m.name;
      EXPECT_LT(t, n) << m.name;
      if (t >= 0) used.insert(t);
    }
  EXPECT_EQ(used.size(), a.assets.textures.size()) << "every texture is some material's";
  for (const Texture& t : a.assets.textures) {
    EXPECT_TRUE(t.width == 256 || t.width == 512) << t.name;
    EXPECT_EQ(t.width, t.height) << t.name;
    EXPECT_EQ(t.rgba.size(), size_t(t.width) * size_t(t.height) * 4) << t.name;
  }
}

TEST(Atrium, MeshesAreFiniteAndWellFormed) {
  const Atrium& a = atrium();
  for (const Mesh& m : a.assets.meshes) {
    ASSERT_EQ(m.triangles.size(), m.materials.size()) << m.name;
    ASSERT_EQ(m.tangents.size(), m.vertices.size()) << m.name;
    for (const Vertex& v : m.vertices) {
      ASSERT_TRUE(std::isfinite(v.position.x) && std::isfinite(v.position.y) &&
                  std::isfinite(v.position.z))
          << m.name;
      ASSERT_NEAR(glm::length(v.normal), 1.0f, 1e-3f) << m.name;
      ASSERT_LE(std::abs(v.position.x), 16.0f) << m.name;  // within the end walls
    }
    for (const glm::vec4& t : m.tangents) ASSERT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-3f);
    for (size_t k = 0; k < m.triangles.size(); ++k) {
      ASSERT_LT(m.triangles[k].x, m.vertices.size());
      ASSERT_LT(m.triangles[k].y, m.vertices.size());
      ASSERT_LT(m.triangles[k].z, m.vertices.size());
      ASSERT_LT(m.materials[k], a.assets.materials.size());
    }
  }
}

TEST(Atrium, GeneratorWritesTheSameBytesEveryRun) {
  const ScratchDir dir;
  generate(dir / "a.glb");
  generate(dir / "b.glb");
  const std::string a = read_bytes(dir / "a.glb"), b = read_bytes(dir / "b.glb");
  ASSERT_GT(a.size(), 1000000u);
  EXPECT_TRUE(a == b) << "two runs wrote different files";
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a(a)));
  EXPECT_EQ(fnv1a(a), kAtriumGlbHash) << "the atrium's file changed (FNV-1a " << hex
                                      << "): if on purpose, bump kAtriumVersion and this hash";

  // What the loader reads back is what was built.
  const LoadedScene loaded = load_gltf((dir / "a.glb").string());
  EXPECT_EQ(loaded.assets.textures.size(), atrium().assets.textures.size());
  EXPECT_EQ(loaded.assets.materials.size(), atrium().assets.materials.size());
  EXPECT_EQ(loaded.lights.size(), atrium().frame.lights.size());
  EXPECT_TRUE(loaded.warnings.empty());
}

}  // namespace
}  // namespace rp::scene
