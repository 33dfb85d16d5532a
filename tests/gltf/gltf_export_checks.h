// What the exporter's tests (gltf_export_test.cpp, gltf_export_round_trip_test.cpp) share: the
// frames they export, and what they read back from a file without the loader: the GLB container
// or the .gltf's data URI checked against glTF 2.0's structural rules, and typed reads of its
// accessors and buffer views.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "scene/frame_scene.h"
#include "scene/gltf_export.h"

namespace rp::test::gltf_export_checks {

struct ExportedFile {
  nlohmann::json doc;
  std::string bin;                    // buffer 0's bytes (byteLength of them)
  std::vector<std::string> problems;  // every rule the file breaks, with where
};

// Reads `file` (.glb by its magic, else .gltf JSON) and checks: the GLB header and chunks
// (lengths, 4-byte padding with spaces / zeros, buffer 0 in the BIN chunk), the data URI's
// length, asset.version, required top-level properties and non-empty arrays, indices in range,
// buffer views (4-byte aligned, inside the buffer), accessors (component alignment, inside
// their views), primitives (POSITION with exact min/max, unit normals and tangents, index
// values, equal attribute counts), nodes, materials, textures, images (PNG), samplers,
// cameras, KHR_lights_punctual lights, and extensionsUsed naming every extension used and no
// extensionsRequired.
ExportedFile read_exported(const std::filesystem::path& file);

// The problems as one line each, for a failure message.
std::string describe(const std::vector<std::string>& problems);

// Accessor `index`'s values, all components in order; FLOAT accessors only.
std::vector<float> floats(const ExportedFile& f, int index);
// An index accessor's values (unsigned short or int).
std::vector<uint32_t> indices(const ExportedFile& f, int index);
// A buffer view's bytes.
std::string view_bytes(const ExportedFile& f, int index);

// ---- frames to export (gltf_export_frames.cpp) ----

// A folder under the test temp dir, removed with everything in it.
class ExportFolder {
 public:
  ExportFolder();
  ~ExportFolder();
  ExportFolder(const ExportFolder&) = delete;
  ExportFolder& operator=(const ExportFolder&) = delete;
  std::filesystem::path file(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

const scene::SceneAssets& demo_assets();
scene::ExportOptions demo_options();          // the demo's GI volume, [-1,1]^3
scene::FrameScene demo_frame_with_marbles();  // the demo frame and two resting marbles

// One mesh with two materials (a quad and a triangle) and tangents; the first material has
// every texture (base colour with clamp / mirrored wrap, normal map, metallic-roughness,
// emission), MASK, double-sided, emission above 1; the second is a metal. No lamp; a
// directional, a point (with range), a spot and a hard-edged spot light.
struct SyntheticScene {
  scene::SceneAssets assets;
  scene::FrameScene frame;
};
SyntheticScene synthetic_scene();

// The object-space corners of `mesh`'s triangles in the order the exporter writes them (and
// the loader merges them back): grouped by material index, ascending, the mesh's order within.
std::vector<glm::vec3> corners_by_material(const scene::Mesh& mesh);
std::map<uint32_t, size_t> triangles_per_material(const scene::Mesh& mesh);

// KHR_materials_ior's index back to the coat's reflectance at normal incidence.
double f0_of_ior(double ior);

}  // namespace rp::test::gltf_export_checks
