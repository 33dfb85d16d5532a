// A texture too large for the device is named before any mip chain is built. A
// 16384x16384 wood.png used to fail at clCreateBuffer after 45 s and 12 GiB of host memory,
// reported as "the device ran out of memory for a 16x16 image" (the frame size). The check
// reads only the textures' sizes, so the textures here hold no pixels.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cl/error.h"
#include "render/gpu_scene.h"

namespace rp::render {
namespace {

constexpr uint64_t kMiB = uint64_t(1) << 20;

scene::Texture sized(const std::string& name, int width, int height) {
  scene::Texture t;
  t.name = name;
  t.width = width;
  t.height = height;
  return t;
}

std::string message_of(const std::vector<scene::Texture>& textures, uint64_t max_alloc,
                       uint64_t global) {
  try {
    check_texture_memory(textures, max_alloc, global);
  } catch (const rp::cl::Error& e) {
    return e.what();
  }
  return "";
}

TEST(TextureMemory, TooLargeForOneBufferNamesTheTextureAndTheLimit) {
  // A device with 1 GiB per buffer and 15 GiB in all (PoCL on the CI machine allows 4 GiB per
  // buffer: since the textures are kept packed only, 4 B a texel, this pair fits there).
  const std::vector<scene::Texture> textures = {sized("wood", 16384, 16384),
                                                sized("tumbler_face", 256, 256)};
  const std::string m = message_of(textures, 1024 * kMiB, 15450 * kMiB);
  EXPECT_NE(m.find("texture 'wood' is 16384x16384 texels"), std::string::npos) << m;
  EXPECT_NE(m.find("one buffer of 1366 MiB"), std::string::npos) << m;  // 4 B a texel
  EXPECT_NE(m.find("at most 1024 MiB per buffer"), std::string::npos) << m;
  EXPECT_EQ(m.find("16x16"), std::string::npos) << m;
}

TEST(TextureMemory, TooLargeForTheDeviceNamesItsMemory) {
  // 4096^2 with its chain: 85.3 MiB packed
  const std::string m = message_of({sized("wood", 4096, 4096)}, 512 * kMiB, 64 * kMiB);
  EXPECT_NE(m.find("the textures need 86 MiB"), std::string::npos) << m;
  EXPECT_NE(m.find("but the device has 64 MiB"), std::string::npos) << m;
}

TEST(TextureMemory, TexturesThatFitPass) {
  EXPECT_EQ(message_of({sized("wood", 512, 512), sized("tumbler_face", 256, 256)}, 4096 * kMiB,
                       15450 * kMiB),
            "");
  // Exactly at the limit: 1x1 texture = 1 texel = 4 bytes packed.
  EXPECT_EQ(message_of({sized("dot", 1, 1)}, 4, 4), "");
  EXPECT_NE(message_of({sized("dot", 1, 1)}, 3, 4), "");
  EXPECT_NE(message_of({sized("dot", 1, 1)}, 4, 3), "");
  EXPECT_EQ(message_of({}, 1, 1), "");  // no texture, nothing to check
  EXPECT_EQ(message_of({sized("wood", 512, 512)}, 0, 0), "");  // the driver did not say
}

}  // namespace
}  // namespace rp::render
