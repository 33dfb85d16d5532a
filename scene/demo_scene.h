// The demo scene of SPEC.md section 1: the Cornell box, the ceiling lamp and five tumblers.
// Tests, the bench and the app all build their frames from here.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "scene/frame_scene.h"
#include "scene/tumbler_shape.h"

namespace rp::scene {

// Indices into SceneAssets built by make_demo_assets().
namespace demo {
inline constexpr uint32_t kBoxMesh = 0, kLampMesh = 1, kTumblerMesh = 2;
// The tumbler's proxy (Mesh::proxy): a third of its triangles (24 segments, rings 8/2/6 against
// 48 and 12/4/8: 720 triangles against 2208), for the voxelizer up to 64^3 (the default: what
// it spends on tumbler triangles drops to a third) and shadow maps up to 512^2. The proxy's
// vertices lie on the surface and its chords at most 0.0086 r inside it (1 - cos 7.5 degrees;
// r = 0.2 at the bottom). That is 0.06 voxel at 64^3, where it changes 131 of the tumblers'
// 5431 opaque voxels (a rim) and the volume's light by 0.2 %, but 1.3 % of the room's voxels
// at 128^3, so finer volumes voxelize the mesh (VoxelizeDemo.TumblerProxyVoxelizesLikeTheMesh).
// In the default 1024^2 shadow map it is 0.26 texel at the floor (texels 0.0068 wide there),
// and that already moved the contact shadows enough to cost the direct light 0.46 dB on the
// floor against the area-lamp truth (bench --accuracy at 360: 35.46 -> 35.00 dB, penumbra
// 29.3 -> 28.8 dB), so only maps of at most 512^2 (0.13 texel) draw it.
inline constexpr uint32_t kTumblerProxyMesh = 3;
inline constexpr uint32_t kTumblerProxyMaxVoxels = 64;
inline constexpr uint32_t kTumblerProxyMaxShadowTexels = 512;
inline constexpr TumblerMeshParams kTumblerProxyParams{24, 8, 2, 6};
inline constexpr uint32_t kFloorMaterial = 0, kCeilingMaterial = 1, kBackMaterial = 2,
                          kLeftMaterial = 3, kRightMaterial = 4, kLampMaterial = 5,
                          kTumblerMaterial = 6;
inline constexpr uint32_t kWoodTexture = 0, kTumblerTexture = 1;
// The open demo's skylight (world x and z of the ceiling): 1 x 0.5 against the back wall, the
// ceiling's 2 x 4 quads behind the lamp (whose cap reaches 0.34 from the centre), so the sky
// falls on the back wall and the floor behind the tumblers.
inline constexpr glm::vec2 kSkylightMin{-0.5f, -1.0f}, kSkylightMax{0.5f, -0.5f};
inline constexpr int kTumblerCount = 5;

// The demo's surfaces (model in src/shading/brdf.h): every gloss of the scene is set
// here. Dielectric coats with F0 = ((n - 1) / (n + 1))^2: lacquer and varnish n ~ 1.5 (0.04),
// glass n ~ 1.55 (0.046). Walls and ceiling stay matte (no coat).
inline constexpr Specular kFloorSpecular{0.38f, 0.04f, false};    // varnished wood
inline constexpr Specular kTumblerSpecular{0.25f, 0.045f, false}; // lacquered toy
inline constexpr Specular kMarbleSpecular{0.08f, 0.046f, false};  // polished glass marble
}  // namespace demo

// Where a tumbler stands at rest: floor position (x, z) of its bottom sphere centre and its yaw
// (rotation about +y, radians; yaw 0 faces +z, towards the camera).
struct TumblerPlacement {
  glm::vec2 xz;
  float yaw;
};

// The five resting places of the demo: spread over the floor, centres at least 0.57 apart (two
// tumblers touch at 2b = 0.4), bodies at least 0.25 from the side and back walls, each turned roughly towards
// the camera with a little variety.
std::array<TumblerPlacement, demo::kTumblerCount> demo_tumbler_placements();

// Model matrix of an upright tumbler at `placement`: the bottom sphere centre at
// (x, -1 + b, z), so the tumbler touches the floor y = -1.
glm::mat4 upright_tumbler_model(const TumblerShape& shape, const TumblerPlacement& placement);

// The asset folder: $ROLYPOLY_ASSET_DIR if set, else the source tree's scene/assets.
std::string default_asset_dir();

// Meshes (box, lamp cap, tumbler, the tumbler's proxy), materials (walls, lamp, tumbler) and textures (wood.png,
// tumbler_face.png from asset_dir). Throws AssetError when a texture cannot be loaded.
// open: the half-open variant (`--open`): a skylight, demo::kSkylight, cut into the ceiling, so
// a sky (--env, --sky) lights the room through it as well as through the open front.
SceneAssets make_demo_assets(const std::string& asset_dir, bool open = false);

// The demo at rest: default camera and light, the box and lamp (identity model, no shadow), five
// upright tumblers at demo_tumbler_placements() (casting shadows). Previous camera and models
// equal the current ones (no motion).
FrameScene make_demo_frame(const SceneAssets& assets, uint32_t frame_index = 0);

// A marble at rest on the floor (y = -1) at floor position (x, z): still (previous centre =
// centre), the simulated marbles' coat (demo::kMarbleSpecular), casting a shadow. The accuracy
// report's frames place them.
Sphere resting_marble(glm::vec2 xz, float radius, glm::vec3 albedo);

// Appends the room's static instances (identity model): the box (no shadow) and the lamp cap
// (no shadow, not voxelized). Shared by the demo frame and the simulated world.
void add_room_instances(FrameScene& frame);

}  // namespace rp::scene
