// `rolypoly export FILE`: the demo's first frame (what `render --frames 1` draws) as glTF.
#include <cstdio>

#include "app/commands.h"
#include "app/pathtrace_settings.h"
#include "app/simulation_source.h"
#include "scene/demo_scene.h"
#include "scene/gltf_export.h"

namespace rp::app {

int export_command(const CommonOptions& common, const ExportOptions& options) {
  const scene::SceneAssets assets = load_demo_assets(common);
  SimulationFrameSource source(make_simulation_options(options.sim, common.render.effects));
  const scene::FrameScene frame = source.next_frame();
  scene::ExportOptions exporting;
  // The demo's GI volume is its box: a loaded export voxelizes on the same grid.
  exporting.volume = scene::Bounds{glm::vec3(-1.0f), glm::vec3(1.0f)};
  scene::export_gltf(assets, frame, options.file, exporting);
  size_t triangles = 0;
  for (const scene::MeshInstance& inst : frame.instances)
    triangles += assets.meshes[inst.mesh].triangles.size();
  std::printf("wrote %s (%zu mesh instances, %zu triangles, %zu spheres, the lamp)\n",
              options.file.c_str(), frame.instances.size(), triangles, frame.spheres.size());
  return 0;
}

}  // namespace rp::app
