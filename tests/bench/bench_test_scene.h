// A small scene file for the bench's tests (bench_file_scene_test.cpp,
// accuracy_file_scene_test.cpp): a floor with a checker texture and a coat, a back wall with an
// emissive patch, two boxes of their own materials, a directional and a spot light, written
// with scene::export_gltf in metres (the loader fits it into render space).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace rp::test {

struct BenchTestScene {
  uint32_t triangles = 0, meshes = 0, instances = 0, textures = 0, lights = 0;
  std::vector<std::string> materials;  // names, in the file's order
};

// Writes the scene as `file` (.gltf or .glb) and says what it holds. `spot_scale` multiplies
// the spot light's intensity: other content with the same meshes, materials and camera.
BenchTestScene write_bench_test_scene(const std::filesystem::path& file,
                                      float spot_scale = 1.0f);

}  // namespace rp::test
