// Debug views (pass "debug_view", kernels/debug_view.cl): one buffer of the frame written as the
// RGBA8 image (uint per pixel, R in the low byte, A = 255, the tone map's output format) in place
// of the normal chain. The views and their colour mappings are documented in the kernel file.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "passes/light.h"
#include "render/frame_buffers.h"
#include "render/gpu_scene.h"
#include "util/named_enum.h"

namespace rp::passes {

enum class DebugView { kFinal, kAlbedo, kNormal, kDepth, kVelocity, kShadowMap, kDirect, kIndirect,
                       kVoxels, kSpecular };

// What to show. level / dir: the voxel volume of the voxels view (dir = RP_DIR_*, ignored at
// level 0).
struct DebugViewSettings {
  DebugView view = DebugView::kFinal;
  uint32_t level = 0;
  uint32_t dir = 0;  // RP_DIR_POS_X
};

// Command-line names (--view, the window title), in DebugView order (util/named_enum.h).
constexpr NamedValue<DebugView> kDebugViewNames[] = {
    {DebugView::kFinal, "final"},         {DebugView::kAlbedo, "albedo"},
    {DebugView::kNormal, "normal"},       {DebugView::kDepth, "depth"},
    {DebugView::kVelocity, "velocity"},   {DebugView::kShadowMap, "shadow-map"},
    {DebugView::kDirect, "direct"},       {DebugView::kIndirect, "indirect"},
    {DebugView::kVoxels, "voxels"},       {DebugView::kSpecular, "specular"}};
constexpr std::span<const NamedValue<DebugView>> names(DebugView) { return kDebugViewNames; }
// Voxel directions "+x", "-x", "+y", "-y", "+z", "-z" <-> RP_DIR_* (0..5).
const char* voxel_dir_name(uint32_t dir);
std::optional<uint32_t> parse_voxel_dir(std::string_view name);
// Window keys: '1' final, '2' albedo, '3' normal, '4' depth, '5' velocity, '6' shadow-map,
// '7' direct, '8' indirect, '9' voxels, '0' specular; anything else: nullopt.
std::optional<DebugView> debug_view_for_key(char key);
// The direct, indirect and specular views need the light pass's components (LightPass::run
// with a LightComponents target).
inline bool needs_light_components(DebugView v) {
  return v == DebugView::kDirect || v == DebugView::kIndirect || v == DebugView::kSpecular;
}

// The buffers a view reads; only those of the selected view must be set.
struct DebugViewInputs {
  const render::GBuffer* gbuffer = nullptr;      // albedo, normal, depth, velocity
  const render::ShadowMap* shadow = nullptr;     // shadow-map
  const LightComponents* light = nullptr;        // direct, indirect, specular
  const ::cl::Buffer* voxels = nullptr;          // voxels: the chain (shared/voxel_layout.h)
  uint32_t voxel_resolution = 0, voxel_levels = 0;
};

class DebugViewPass {
 public:
  // Kernels are built on first use of each view (a debug view costs no start-up time).
  // gi_options: "-DRP_GI_SVO" when the voxels given to run are the sparse voxel octree
  // (kernels/shared/svo_layout.h) instead of the dense chain; "" otherwise.
  DebugViewPass(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
                std::string gi_options = "");

  // Writes `settings.view` into rgba8 (scene.constants.width x height uints). Throws
  // rp::cl::Error for kFinal (the renderer runs tone_map instead), a missing or mis-sized
  // input, or a voxel level / direction out of range.
  void run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
           const DebugViewSettings& settings, const DebugViewInputs& inputs,
           ::cl::Buffer& rgba8);

 private:
  ::cl::Kernel& kernel(const std::string& name);

  rp::cl::ProgramCache* programs_;
  std::string gi_options_;
  std::map<std::string, ::cl::Kernel> kernels_;
};

}  // namespace rp::passes
