#include "app/render_session.h"

#include <stdexcept>

#include "scene/demo_scene.h"

namespace rp::app {
namespace {

// Hands the view to the renderer once it has Renderer::set_debug_view (issue 4 wiring); until
// then only the final image exists. A template so that the requires-expression is checked when
// instantiated (a false one is then not an error). Remove the fallback once the renderer has it.
template <typename R>
void apply_view(R& renderer, const passes::DebugViewSettings& view) {
  if constexpr (requires { renderer.set_debug_view(view); }) {
    renderer.set_debug_view(view);
  } else if (view.view != passes::DebugView::kFinal) {
    throw std::runtime_error(std::string("--view ") + passes::debug_view_name(view.view) +
                             ": this build's renderer does not run the debug views yet");
  }
}

}  // namespace

RenderSession::RenderSession(const CommonOptions& options, uint32_t width, uint32_t height)
    : assets_(scene::make_demo_assets(options.asset_dir.empty() ? scene::default_asset_dir()
                                                                : options.asset_dir)),
      context_(rp::cl::Context::create(options.device)),
      programs_(context_) {
  render::RenderSettings settings;
  settings.width = width;
  settings.height = height;
  if (options.shadow_size != 0) settings.shadow_size = options.shadow_size;
  renderer_ = std::make_unique<render::Renderer>(context_, programs_, assets_, settings);
  set_view(options.view);
}

void RenderSession::set_view(const passes::DebugViewSettings& view) {
  apply_view(*renderer_, view);
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
