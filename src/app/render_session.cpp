#include "app/render_session.h"

#include "scene/demo_scene.h"

namespace rp::app {
RenderSession::RenderSession(const CommonOptions& options, uint32_t width, uint32_t height)
    : assets_(scene::make_demo_assets(options.asset_dir.empty() ? scene::default_asset_dir()
                                                                : options.asset_dir)),
      context_(rp::cl::Context::create(options.device)),
      programs_(context_) {
  render::RenderSettings settings;
  settings.width = width;
  settings.height = height;
  if (options.shadow_size != 0) settings.shadow_size = options.shadow_size;
  if (options.voxels != 0) settings.voxel_resolution = options.voxels;
  settings.effects = options.effects;
  settings.visibility = options.visibility;
  renderer_ = std::make_unique<render::Renderer>(context_, programs_, assets_, settings);
  set_view(options.view);
}

void RenderSession::set_view(const passes::DebugViewSettings& view) {
  renderer_->set_debug_view(view);
  view_ = view;
}

rp::cl::PassTimes RenderSession::render(const scene::FrameScene& frame,
                                        std::vector<uint8_t>& rgba, double& frame_ms) {
  auto start = std::chrono::steady_clock::now();
  rp::cl::PassTimes times = renderer_->render(frame);
  frame_ms = ms_since(start);
  renderer_->read_rgba8(rgba);
  return times;
}

std::string describe_device(const rp::cl::DeviceInfo& info) {
  std::string text = "[";  // appends, not operator+ chains: GCC 12 -Wrestrict false positive
  text += std::to_string(info.index);
  text += "] ";
  text += info.name;
  text += " (";
  text += info.type;
  text += ", ";
  text += info.platform_name;
  text += ")";
  return text;
}

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace rp::app
