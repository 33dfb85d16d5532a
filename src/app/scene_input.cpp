#include "app/scene_input.h"

#include <cstdio>

#include "render/gpu_types.h"

namespace rp::app {

FileScene open_scene_file(const std::string& path) {
  FileScene scene;
  scene.path = path;
  scene.loaded = scene::load_gltf(path);
  for (const std::string& warning : scene.loaded.warnings)
    std::fprintf(stderr, "rolypoly: warning: %s: %s\n", path.c_str(), warning.c_str());
  if (const size_t n = scene.loaded.lights.size(); n > RP_MAX_PUNCTUAL_LIGHTS)
    std::fprintf(stderr,
                 "rolypoly: warning: %s: %zu punctual lights; the real-time passes draw the "
                 "first %u (the path tracer all of them)\n",
                 path.c_str(), n, RP_MAX_PUNCTUAL_LIGHTS);
  scene.fit = scene::fit_volume(scene.loaded);
  scene.camera = scene::initial_camera(scene.loaded);
  return scene;
}

scene::FrameScene FileFrameSource::next() {
  scene::FrameScene frame =
      scene::make_file_frame(scene_.loaded, scene_.fit, camera_, previous_, frames_);
  if (scene_.loaded.lamp) {
    // The demo's lamp carried by an exported demo: in render space like everything else (its
    // intensity scales as a point light's, its radius and clip planes as lengths).
    scene::PointLight lamp = *scene_.loaded.lamp;
    lamp.position = scene_.fit.to_render(lamp.position);
    lamp.intensity *= scene_.fit.scale * scene_.fit.scale;
    lamp.lamp_radius *= scene_.fit.scale;
    lamp.shadow_near *= scene_.fit.scale;
    lamp.shadow_far *= scene_.fit.scale;
    frame.light = lamp;
    frame.lamp = true;
  }
  previous_ = camera_;
  ++frames_;
  return frame;
}

}  // namespace rp::app
