// The renderer's view of a loaded scene file (scene/gltf_loader.h).
//
// Render space: the renderer, its kernels and the path tracer draw every scene in one frame of
// reference, where the GI volume is the cube [-1,1]^3 (the demo's box). A file's world (glTF
// metres, from millimetre props to 100 m buildings) is mapped there by one similarity
// transform, VolumeFit: a uniform scale and a translation. So every world-to-voxel conversion,
// ray offset, shadow bias and cone step tuned in units of the volume holds for any scene, and
// this is the one place that knows a scene's size. Light units stay consistent: directions and
// emitted radiance do not change under the map; a point or spot light's intensity is
// multiplied by scale^2 (its light falls off as 1/d^2 and distances grow by `scale`), its range
// by `scale`; directional light is irradiance and stays as it is.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "scene/frame_scene.h"
#include "scene/gltf_loader.h"

namespace rp::scene {

struct VolumeFit {
  glm::vec3 center{0.0f};  // world point mapped to the origin
  float scale = 1.0f;      // render units per world unit: the volume's half side is 1 / scale
  glm::vec3 to_render(glm::vec3 world) const { return (world - center) * scale; }
  glm::vec3 to_world(glm::vec3 render) const { return render / scale + center; }
  glm::mat4 matrix() const;  // world -> render
  // The world cube the GI volume covers.
  Bounds world_volume() const;
};

// The GI volume of a scene: the file's own (LoadedScene::volume) when it names one, else the
// cube around its bounds, `margin` of the largest side added on each side (a flat or empty
// extent is widened so the cube is never degenerate).
VolumeFit fit_volume(const LoadedScene& scene, float margin = 0.05f);

// The camera a file scene opens with (world units): the file's, else one looking at the
// bounds' centre from the +z side, slightly above, far enough to see all of them with a 60
// degree view; near and far planes from the bounds.
Camera initial_camera(const LoadedScene& scene);

// The frame of a static file scene seen from `camera` (world units) after `previous` (the
// previous frame's camera: velocity), in render space. Instances as loaded (casting shadows,
// voxelized), the file's lights, no demo lamp, no spheres.
FrameScene make_file_frame(const LoadedScene& scene, const VolumeFit& fit, const Camera& camera,
                           const Camera& previous, uint32_t frame_index);

// `camera` (world units) in render space.
Camera to_render_space(const Camera& camera, const VolumeFit& fit);

}  // namespace rp::scene
