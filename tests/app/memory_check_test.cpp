// Memory checked before it is taken, in every mode: the GI volume (dense chain or octree) and a
// loaded scene are counted against the device before any allocation, and the message names the
// setting that decides (--voxels, the scene) with what fits; an allocation the driver still
// refuses names what was being allocated. A --scene file larger than the host memory the
// process may take is refused before it is read.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "app/render_session.h"
#include "app/scene_input.h"
#include "cl/buffer.h"
#include "cl/error.h"
#include "support/cl_fixture.h"
#include "support/cli_runner.h"

namespace rp::test {
namespace {

namespace fs = std::filesystem;

cl::DeviceInfo device_with(uint64_t global_mib, uint64_t max_alloc_mib) {
  cl::DeviceInfo device;
  device.name = "small";
  device.global_mem_bytes = global_mib << 20;
  device.max_alloc_bytes = max_alloc_mib << 20;
  return device;
}

render::RenderSettings settings_for(uint32_t size, uint32_t voxels, bool octree) {
  render::RenderSettings s;
  s.width = s.height = size;
  s.shadow_size = 1024;
  s.voxel_resolution = voxels;
  s.gi_volume = octree ? render::GiVolume::kSvo : render::GiVolume::kDense;
  return s;
}

std::string check_message(const cl::DeviceInfo& device, uint32_t size, uint32_t voxels,
                          bool octree, const app::SceneMemory* scene = nullptr) {
  try {
    app::check_device_memory(device, settings_for(size, voxels, octree), {}, scene,
                             "--scene big.glb");
  } catch (const cl::Error& e) {
    return e.what();
  }
  return "";
}

// What PoCL reports under POCL_MEMORY_LIMIT=1: 1 GiB of global memory, 256 MiB per buffer.
TEST(MemoryCheck, OctreeTooLargeAtThisSizeNamesTheLargestVoxelsThatFit) {
  const cl::DeviceInfo device = device_with(1024, 256);
  // 2200^2: the image's buffers take about 900 MiB; the octree at 512^3 160 MiB more does not
  // fit, at 256^3 (40 MiB) it does.
  const std::string m = check_message(device, 2200, 512, true);
  EXPECT_TRUE(Contains(m, "--gi-volume svo --voxels 512 at 2200x2200 needs "));
  EXPECT_TRUE(Contains(m, " MiB of device memory (the image's buffers "));
  EXPECT_TRUE(Contains(m, "the octree 160 MiB"));
  EXPECT_TRUE(Contains(m, "the device has 1024 MiB"));
  EXPECT_TRUE(Contains(m, "the largest --voxels that fits at this size is 256 (--voxels 256)"));
  const uint32_t side = app::largest_square_that_fits(
      device.global_mem_bytes, device.max_alloc_bytes, settings_for(0, 512, true));
  ASSERT_GT(side, 0u);
  EXPECT_TRUE(Contains(m, "or at --voxels 512 the largest square size is about " +
                              std::to_string(side) + " (--size " + std::to_string(side) + ")"));
  EXPECT_EQ(check_message(device, 2200, 256, true), "");
}

TEST(MemoryCheck, DenseVolumeTooLargeNamesTheLargestVoxelsThatFit) {
  // 600 MiB: at 1500^2 (about 420 MiB of image buffers) the dense chain at 128^3 (136 MiB)
  // does not fit, at 64^3 (17 MiB) it does.
  const cl::DeviceInfo device = device_with(600, 512);
  const std::string m = check_message(device, 1500, 128, false);
  EXPECT_TRUE(Contains(m, "--gi-volume dense --voxels 128 at 1500x1500 needs "));
  EXPECT_TRUE(Contains(m, "the dense GI volume "));
  EXPECT_TRUE(Contains(m, "the largest --voxels that fits at this size is 64 (--voxels 64)"));
  EXPECT_EQ(app::largest_voxels_that_fit(device.global_mem_bytes, device.max_alloc_bytes,
                                         settings_for(1500, 128, false)),
            64u);
}

TEST(MemoryCheck, VolumeBufferAboveTheLargestAllocationNamesIt) {
  // The octree's fragment list at 512^3 is one buffer of about 80 MiB: above a 64 MiB limit.
  const std::string m = check_message(device_with(8192, 64), 64, 512, true);
  EXPECT_TRUE(Contains(m, "--gi-volume svo --voxels 512 at 64x64 needs one buffer of 80 MiB "
                          "for the octree's fragment list, the device allows at most 64 MiB per "
                          "buffer; the largest --voxels that fits at this size is 256"));
}

TEST(MemoryCheck, ImageTooLargeStillSuggestsASize) {
  // No --voxels helps at 16384^2: the message is the size's, as before.
  const std::string m = check_message(device_with(2048, 1024), 16384, 64, false);
  EXPECT_TRUE(Contains(m, "16384x16384 needs "));
  EXPECT_TRUE(Contains(m, "the largest square size that fits is about "));
  EXPECT_EQ(m.find("--voxels"), std::string::npos) << m;
}

TEST(MemoryCheck, LoadedSceneTooLargeNamesItsSizes) {
  app::SceneMemory scene;
  scene.vertices = 20'000'000;  // 20 M vertices at 48 bytes: 915 MiB, plus the triangles
  scene.triangles = 40'000'000;
  const std::string m = check_message(device_with(1024, 1024), 64, 64, false, &scene);
  EXPECT_TRUE(Contains(m, "the scene --scene big.glb needs 1542 MiB of device memory "
                          "(20000000 vertices, 40000000 triangles, 0 textures"));
  EXPECT_TRUE(Contains(m, "but the device has 1024 MiB; use a smaller scene"));
  // One buffer above the limit: the triangles (610 MiB) on a device of 256 MiB per buffer.
  const std::string one = check_message(device_with(8192, 256), 64, 64, false, &scene);
  EXPECT_TRUE(Contains(one, "one buffer of 611 MiB, but the device allows at most 256 MiB per "
                            "buffer; use a smaller scene"));
  // A scene that fits adds its own buffers to the estimate instead of the fixed reserve.
  app::SceneMemory small;
  small.triangles = 4'000'000;
  small.vertices = 2'000'000;
  EXPECT_GT(app::estimate_device_memory(settings_for(64, 64, false), {}, &small).total_bytes,
            app::estimate_device_memory(settings_for(64, 64, false)).total_bytes);
}

TEST(MemoryCheck, SceneMemoryCountsMeshesAndMipChains) {
  scene::SceneAssets assets;
  scene::Mesh mesh;
  mesh.vertices.resize(10);
  mesh.triangles.resize(4);
  assets.meshes.push_back(mesh);
  scene::Texture texture;
  texture.width = 4;
  texture.height = 2;
  assets.textures.push_back(texture);
  const app::SceneMemory m = app::count_scene_memory(assets);
  EXPECT_EQ(m.vertices, 10u);
  EXPECT_EQ(m.triangles, 4u);
  EXPECT_EQ(m.textures, 1u);
  EXPECT_EQ(m.texels, 8u + 2u + 1u);  // 4x2, 2x1, 1x1
  EXPECT_EQ(m.bytes(), 10u * 48 + 4u * 16 + 11u * 4);
}

// An allocation the driver refuses names what it was for and its size.
TEST(MemoryCheck, FailedAllocationNamesWhatWasBeingAllocated) {
  const cl::Context& ctx = context();
  const uint64_t max_alloc = ctx.info.max_alloc_bytes;
  ASSERT_GT(max_alloc, 0u);
  const size_t bytes = size_t(max_alloc) + (size_t(1) << 30);  // above the largest allocation
  try {
    rp::cl::make_buffer(ctx.context, CL_MEM_READ_WRITE, bytes, "the test's buffer",
                        "a smaller one needs less");
    GTEST_SKIP() << "the driver allocated beyond CL_DEVICE_MAX_MEM_ALLOC_SIZE";
  } catch (const cl::Error& e) {
    const std::string m = e.what();
    EXPECT_TRUE(Contains(m, "allocating the test's buffer (" +
                                std::to_string((bytes + (1u << 20) - 1) >> 20) +
                                " MiB) failed: "));
    EXPECT_TRUE(Contains(m, " of global memory, at most " + std::to_string(max_alloc >> 20) +
                                " MiB in one buffer); a smaller one needs less"));
  }
}

bool device_zero_is_pocl() {
  const CommandResult devices = run_rolypoly("devices");
  return devices.out.find("Portable Computing Language") != std::string::npos;
}

// The binary under PoCL's POCL_MEMORY_LIMIT (GiB): the octree's --voxels is named before any
// kernel is built or buffer allocated.
TEST(MemoryCheck, CliOctreeBeyondTheDeviceNamesVoxels) {
  if (!device_zero_is_pocl()) GTEST_SKIP() << "POCL_MEMORY_LIMIT needs PoCL as device 0";
  TempDir dir;
  const CommandResult r = run_rolypoly(
      "render --gi-volume svo --voxels 512 --size 2200 --out " +
          shell_quote((dir / "out").string()),
      "POCL_MEMORY_LIMIT=1");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(Contains(r.err, "rolypoly: error: --gi-volume svo --voxels 512 at 2200x2200 needs "));
  EXPECT_TRUE(Contains(r.err, "the device has 1024 MiB; the largest --voxels that fits at this "
                              "size is 256 (--voxels 256)"));
  EXPECT_EQ(r.err.find("kernel"), std::string::npos) << r.err;
  EXPECT_TRUE(entries(dir.path()).empty() || entries(dir / "out").empty());
}

// A --scene file larger than what `ulimit -v` leaves is refused before it is read (a sparse
// file: no disk is used), with exit 1 (the file is not at fault), naming the file and the limit.
TEST(MemoryCheck, CliSceneFileBeyondTheProcessLimitIsRefusedBeforeReading) {
  TempDir dir;
  const fs::path big = dir / "big.glb";
  {
    std::ofstream f(big, std::ios::binary);
    f << "glTF";
  }
  fs::resize_file(big, uint64_t(3) << 30);  // 3 GiB, sparse
  const CommandResult r = run_rolypoly(
      "render --size 16 --scene " + shell_quote(big.string()) + " --out " +
          shell_quote((dir / "out").string()),
      "bash -c " + shell_quote("ulimit -v 2097152; exec \"$0\" \"$@\"") + " ");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(Contains(r.err, "rolypoly: error: --scene " + big.string() +
                                  " is 3072 MiB; loading it needs at least that much host "
                                  "memory"));
  EXPECT_TRUE(std::regex_search(r.err, std::regex("more \\(ulimit -v 2097152\\)|GiB available")))
      << r.err;
}

TEST(MemoryCheck, SceneFileCheckComparesTheFileWithTheHostMemory) {
  TempDir dir;
  const fs::path file = dir / "s.glb";
  write_plain(file, std::string(4096, 'x'));
  app::HostMemory memory;
  memory.available_bytes = 1024;
  memory.source = "the process may take 0.0 GiB more (ulimit -v 1)";
  try {
    app::check_scene_file_memory(file.string(), memory);
    FAIL() << "4096 bytes do not fit in 1024";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(Contains(e.what(), "--scene " + file.string() + " is 1 MiB; loading it needs "));
    EXPECT_TRUE(Contains(e.what(), "the process may take 0.0 GiB more (ulimit -v 1)"));
  }
  memory.available_bytes = 8192;
  EXPECT_NO_THROW(app::check_scene_file_memory(file.string(), memory));
  memory.available_bytes = 0;  // unknown: nothing is refused
  EXPECT_NO_THROW(app::check_scene_file_memory(file.string(), memory));
}

}  // namespace
}  // namespace rp::test
