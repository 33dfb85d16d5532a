#include "app/scene_input.h"

#include <cstdio>
#include <new>
#include <stdexcept>

#include <sys/resource.h>
#include <sys/stat.h>

#include "app/atrium_scene.h"
#include "app/host_memory.h"
#include "app/input_file.h"
#include "render/gpu_types.h"

namespace rp::app {

void check_scene_file_memory(const std::string& path, const HostMemory& memory) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || memory.available_bytes == 0) return;
  const uint64_t size = uint64_t(st.st_size);
  if (size <= memory.available_bytes) return;
  const auto mib = [](uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20); };
  throw std::runtime_error("--scene " + path + " is " + mib(size) +
                           " MiB; loading it needs at least that much host memory (the file is "
                           "read whole, then its textures decoded), " + memory.source);
}

FileScene open_scene_file(const std::string& name) {
  // "atrium": the generated courtyard, written once into the cache (app/atrium_scene.h).
  const std::string path = is_atrium_scene(name) ? atrium_scene_file().string() : name;
  FileScene scene;
  scene.path = path;
  require_regular_file(path, "--scene");
  check_scene_file_memory(path, host_memory());
  try {
    scene.loaded = scene::load_gltf(path);
  } catch (const std::bad_alloc&) {
    throw std::runtime_error("loading --scene " + path +
                             " ran out of host memory (its buffers and decoded textures)" +
                             memory_limit_note());
  }
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

std::string describe_file_scene(const FileScene& scene) {
  const scene::LoadedScene& l = scene.loaded;
  uint64_t triangles = 0;
  for (const scene::MeshInstance& inst : l.instances)
    triangles += l.assets.meshes[inst.mesh].triangles.size();
  char text[640];
  std::snprintf(text, sizeof text,
                "scene %s: %llu triangles drawn (%zu instances of %zu meshes), %zu textures, "
                "%zu lights; loaded in %.0f ms (read %.0f, parse %.0f, accessors %.0f, images "
                "decoded %.0f)",
                scene.path.c_str(), static_cast<unsigned long long>(triangles),
                l.instances.size(), l.assets.meshes.size(), l.assets.textures.size(),
                l.lights.size(), l.times.total_ms, l.times.read_ms, l.times.parse_ms,
                l.times.accessors_ms(), l.times.decode_ms);
  return text;
}

std::string describe_host_memory() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  char text[64];
  std::snprintf(text, sizeof text, "host memory: peak %.0f MiB",
                double(usage.ru_maxrss) / 1024.0);  // Linux: kilobytes
  return text;
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
