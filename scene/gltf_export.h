// Writing one frame of a scene (the demo's, or any FrameScene) as a glTF 2.0 file that
// scene/gltf_loader.h reads back: the meshes the frame's instances draw, its spheres as
// tessellated meshes, materials with their textures as embedded PNGs, the lights, the camera,
// and the renderer-only settings (GI volume, the demo's lamp, shadow and voxel flags) as
// "rolypoly" extras. Units stay the scene's (the demo's box spans [-1,1]^3, read as metres).
#pragma once

#include <filesystem>
#include <optional>

#include "scene/frame_scene.h"

namespace rp::scene {

struct ExportOptions {
  // Written as the scene's extras {"rolypoly": {"volume": [x0, y0, z0, x1, y1, z1]}}, the GI
  // volume the loader then voxelizes (LoadedScene::volume); none: the loader fits one.
  std::optional<Bounds> volume;
};

// Writes `frame` as `path`: a binary .glb, or a .gltf (JSON with the buffer embedded as a
// base64 data URI) when the extension is ".gltf" (any case). The file appears complete or not
// at all (rp::io::write_file).
//
// What is written:
//  - one glTF mesh per scene Mesh that an instance draws (proxies and unused meshes are left
//    out), one primitive per material its triangles use; one node per MeshInstance, its model
//    matrix as the node's `matrix`, and node extras {"rolypoly": {"casts_shadow": false,
//    "voxelize": false}} for the flags that are not true;
//  - spheres as nodes scaling and moving a unit UV sphere (within 0.1 % of the radius), one
//    glTF mesh per distinct sphere material, all sharing one copy of the geometry;
//  - materials as metallic-roughness with KHR_materials_ior (the coat's f0) and, for
//    emission above 1, KHR_materials_emissive_strength;
//  - the demo's lamp (frame.lamp) and frame.lights as KHR_lights_punctual lights, the lamp with
//    extras {"rolypoly": {"lamp": {...}}} so the loader restores it as LoadedScene::lamp;
//  - the camera as a perspective camera (no aspect ratio: the viewer's window decides).
// Motion (prev_model, prev_camera, prev_center) is not written: a file holds one still frame.
//
// Throws std::invalid_argument when the frame refers to meshes, materials or textures that
// `assets` lacks, or a mesh is malformed (index out of range, per-triangle materials or tangents
// not matching), and io::WriteError when the file cannot be written.
void export_gltf(const SceneAssets& assets, const FrameScene& frame,
                 const std::filesystem::path& path, const ExportOptions& options = {});

}  // namespace rp::scene
