// What a command draws: the built-in demo (the simulated Cornell box: SimulationFrameSource)
// or a scene file (glTF 2.0, static: FileFrameSource). `--scene demo` or `--scene FILE`.
#pragma once

#include <cstdint>
#include <string>

#include "app/frame_source.h"
#include "app/host_memory.h"
#include "scene/file_scene.h"
#include "scene/gltf_loader.h"

namespace rp::app {

inline constexpr const char* kDemoScene = "demo";
inline bool is_demo_scene(const std::string& scene) { return scene == kDemoScene; }

// A loaded scene file, fitted to the GI volume (scene/file_scene.h), with the camera it opens
// with (world units).
struct FileScene {
  std::string path;
  scene::LoadedScene loaded;
  scene::VolumeFit fit;
  scene::Camera camera;
};

// Loads the file `name` (scene::SceneFileError: the app's exit status 2), or for "atrium" the
// generated courtyard's cached file (app/atrium_scene.h; FileScene::path is that file), prints
// each warning once on stderr ("rolypoly: warning: FILE: ...") and fits the volume. Checks the
// host memory first (check_scene_file_memory); a loader that still runs out of it gives
// std::runtime_error "loading --scene FILE ran out of host memory ..." (exit 1, not 2: the file
// is not at fault).
FileScene open_scene_file(const std::string& name);

// Throws std::runtime_error when the file at `path` is larger than what `memory` says the
// process may still take: the loader reads it whole before anything else ("--scene big.glb is
// 1536 MiB; loading it needs at least that much host memory (...), the process may take 0.9 GiB
// more (ulimit -v 1048576)"). Nothing when either size is unknown.
void check_scene_file_memory(const std::string& path, const HostMemory& memory);

// "scene FILE: N triangles drawn (I instances of M meshes), T textures, L lights; loaded in
// X ms (read R, parse P, accessors A, images decoded D)" (LoadedScene::Times)
std::string describe_file_scene(const FileScene& scene);

// "host memory: peak N MiB" (the process's peak resident set, getrusage).
std::string describe_host_memory();

// The same frame every time, seen from a camera the caller may move between frames (the
// window's fly camera); the previous frame's camera gives the velocity.
class FileFrameSource final : public FrameSource {
 public:
  explicit FileFrameSource(const FileScene& scene)
      : scene_(scene), camera_(scene.camera), previous_(scene.camera) {}
  scene::FrameScene next() override;
  uint32_t frames_produced() const override { return frames_; }
  // Where the next frame is seen from (world units).
  void set_camera(const scene::Camera& camera) { camera_ = camera; }
  const scene::Camera& camera() const { return camera_; }

 private:
  const FileScene& scene_;
  scene::Camera camera_, previous_;
  uint32_t frames_ = 0;
};

}  // namespace rp::app
