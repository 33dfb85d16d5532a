#include "app/atrium_scene.h"

#include <chrono>
#include <cstdio>
#include <system_error>

#include "app/truth_cache.h"
#include "io/output_path.h"
#include "scene/atrium.h"
#include "scene/gltf_export.h"

namespace rp::app {

std::filesystem::path atrium_cache_file() {
  return default_truth_cache_dir().parent_path() / "scenes" /
         (std::string(scene::kAtriumVersion) + ".glb");
}

std::filesystem::path atrium_scene_file() {
  const std::filesystem::path file = atrium_cache_file();
  std::error_code ec;
  if (std::filesystem::is_regular_file(file, ec)) return file;
  const auto start = std::chrono::steady_clock::now();
  std::filesystem::create_directories(file.parent_path(), ec);
  if (ec) throw io::WriteError(file.parent_path(), ec.message());
  const scene::Atrium atrium = scene::make_atrium();
  scene::export_gltf(atrium.assets, atrium.frame, file);
  std::fprintf(stderr, "rolypoly: generated the atrium into %s in %.1f s\n", file.c_str(),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return file;
}

}  // namespace rp::app
