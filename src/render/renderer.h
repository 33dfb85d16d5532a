// Runs every pass of a frame in order on one device. Knows nothing of physics or windows.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "cl/context.h"
#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "passes/debug_view.h"
#include "passes/light.h"
#include "render/frame_buffers.h"
#include "render/frame_memory.h"
#include "render/gpu_scene.h"
#include "render/render_settings.h"
#include "render/still_volume.h"
#include "render/svo_volume.h"
#include "render/voxel_volume.h"
#include "scene/frame_scene.h"

namespace rp::passes {
class VisibilityPass;
class EmbreeVisibilityPass;
class GBufferPass;
class LightPass;
class PunctualLightPass;
class SkyBackgroundPass;
class PrtSkyPass;
struct PrtShading;
class ShadowFilterPass;
class IndirectPass;
class ToneMapPass;
class TaaUpsamplePass;
class DebugViewPass;
class VoxelizePass;
class VoxelMipsPass;
class SvoPass;
class BouncePass;
class TaaPass;
class BloomPass;
class MotionBlurPass;
}  // namespace rp::passes

namespace rp::render {

// The light pass's linear images read back to the host (Renderer::read_components): RGB, 3
// floats per pixel, row-major, top row first; background pixels 0, but for the sky seen
// directly (0 without one) in combined and emission. The same meaning as
// rp::truth::PathTracedImage's fields: combined = the light pass's HDR output (direct + indirect
// + emission, before post-processing), direct = albedo x lamp light (shadowed), indirect =
// albedo x gathered (cone traced) light, emission and albedo from the GBuffer.
struct LinearComponents {
  uint32_t width = 0, height = 0;
  std::vector<float> combined, direct, indirect, emission, albedo;
  std::vector<float> specular;  // the coat's part of direct + indirect (LightComponents)
};


// Wall-clock milliseconds of the renderer's set-up: the scene's upload (texture mip chains and
// buffers; mips_ms is the chains' part), the Embree visibility backend's BVHs (0 with the
// rasterizer) and the kernel builds (the program cache's: 0.5-4 s each when PoCL's cache is
// cold).
struct SetupTimes {
  double scene_ms = 0.0;
  double mips_ms = 0.0;
  double bvh_ms = 0.0;
  double kernels_ms = 0.0;
};

class Renderer {
 public:
  // Uploads the assets and builds every kernel (throws rp::cl::BuildError with the log).
  Renderer(const rp::cl::Context& context, rp::cl::ProgramCache& programs,
           const scene::SceneAssets& assets, RenderSettings settings);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  const SetupTimes& setup_times() const { return setup_times_; }

  // Reallocates the per-pixel buffers (not per frame: only when the size changes). width x
  // height is the output size.
  void resize(uint32_t width, uint32_t height);
  // Changes the render scale between frames (clamped to [kMinRenderScale, 1]); the render-size
  // buffers follow on the next frame, the output-size history is kept.
  void set_render_scale(float scale);
  // The size the last frame (or the next, before any) was rendered at: the output size scaled
  // for the final view, the output size for debug views.
  uint32_t render_width() const { return render_width_; }
  uint32_t render_height() const { return render_height_; }

  // Enqueues all passes for `frame`, waits, and returns the device time per pass in ms.
  // With VisibilityBackend::kEmbree, "visibility" is the device time of the upload and
  // "visibility_host" the host wall-clock ms of the Embree scene update and ray tracing.
  rp::cl::PassTimes render(const scene::FrameScene& frame);

  // What render() produces: the final image (DebugView::kFinal, the default) or one debug view
  // (passes/debug_view.h), written as RGBA8 in place of the tone map. Throws rp::cl::Error for
  // a voxel level or direction the chain does not have. The direct / indirect views make the
  // light pass also write its two components (two float4 buffers, allocated only then).
  void set_debug_view(const passes::DebugViewSettings& view);
  const passes::DebugViewSettings& debug_view() const { return view_; }
  // The light pass's direct and indirect terms (float4 per pixel), written only while the
  // direct or indirect debug view is on or they are kept (empty buffers otherwise).
  const passes::LightComponents& light_components() const { return light_components_; }
  // Keeps the light pass writing its direct, indirect and specular terms whatever is shown
  // (allocates the three float4 buffers, 48 bytes per pixel, now and on resize), for
  // read_components.
  void set_keep_light_components(bool keep);
  bool keeps_light_components() const { return keep_components_; }
  // Sky light by precomputed radiance transfer from now on (passes/prt_sky.h): `prt` holds the
  // transfer of the frames' instances (the same instances, in the same order, every frame);
  // the diffuse cones and the bounce grid then carry no sky, the reflection cones still do.
  // Where it keeps its shadowed part, the GI volume leaves the environment's suns and the
  // directional lights out too: the transfer gathers their bounces
  // (PrtSkyPass::carries_suns_bounce). Throws rp::cl::Error when the transfer does not fit the
  // scene.
  void set_prt(const passes::PrtShading& prt);
  // Reads the last frame's HDR output, light components and GBuffer emission / albedo back
  // (blocking). Throws rp::cl::Error unless the components were written (a direct / indirect
  // view or set_keep_light_components(true) before the frame).
  void read_components(LinearComponents& out);

  // Switches post-processing effects between frames (turning TAA on starts a fresh history).
  void set_effects(const Effects& effects);
  // Switches the shadow mode between frames (key H in the window; its kernels build on first
  // use).
  void set_shadows(ShadowMode mode);
  // Forgets the TAA history, the fast mode's accumulated indirect light and the bounce grid
  // (the app calls it when the world is reset). Camera cuts, i.e. a frame whose previous
  // camera is not the camera of the frame before, and resizes reset the first two
  // automatically; they keep the bounce grid, which is world-space and view-independent.
  void reset_history();

  // The finished image: width * height * 4 bytes RGBA8, top row first. Blocking.
  void read_rgba8(std::vector<uint8_t>& out);

  const RenderSettings& settings() const { return settings_; }
  // The buffers that follow the frame's size it holds now, part by part as frame_memory()
  // states them (render/frame_memory.h); the shadow map's part includes the punctual lights'
  // maps a file scene adds.
  FrameMemory frame_device_memory() const;
  const GpuScene& gpu_scene() const { return *scene_; }
  const VisibilityBuffer& visibility() const { return vis_; }
  const ShadowMap& shadow_map() const { return shadow_; }
  const GBuffer& gbuffer() const { return gbuffer_; }
  const ::cl::Buffer& hdr() const { return hdr_; }
  const VoxelVolume& voxels() const { return voxels_; }  // the dense volume (kDense)
  const SvoVolume& octree() const { return svo_; }      // the octree (kSvo)
  // The bounce grid (passes/bounce.h) the next frame's voxels take their bounce light from;
  // nullptr with one bounce (settings().bounces < 2) or before the first gather after a reset.
  const ::cl::Buffer* bounce_grid() const;

 private:
  // Gathers of the whole cone set the first frame after a reset iterates (several bounces):
  // each adds a bounce (the rest then converge over the frames: one gather per frame).
  static constexpr uint32_t kWarmGathersFast = 3;
  static constexpr uint32_t kWarmGathersReference = 8;
  // The fast mode refreshes the voxelizer's cached static samples' bounce light a quarter per
  // frame (VoxelizePass::set_bounce_refresh_stride): 0.5 ms of the 720x720 busy frame.
  static constexpr uint32_t kBounceRefreshFast = 4;
  // Frames of unchanged inputs (StillVolume) after which the fast mode keeps its GI volume and
  // bounce grid instead of building them: by then every face of the grid has blended its whole
  // 16-cone set once from the still scene (one face in RP_BOUNCE_FACE_STRIDE = 4 a frame). With
  // one bounce the volume is kept from the first still frame (the same volume, bit for bit).
  static constexpr uint32_t kStillFramesBeforeKeep = 16 * 4;

  // Voxelizes the frame and builds the mips; with several bounces, also the bounce gathers.
  // Keeps the last frame's volume instead where StillVolume allows (see above).
  void build_voxels();

  // The GI volume the cones read: the dense chain or the octree buffer, its resolution and
  // levels (log2 R + 1 for both).
  const ::cl::Buffer& gi_buffer() const;
  uint32_t gi_resolution() const;
  uint32_t gi_levels() const;
  // Forgets the view-dependent histories (TAA, the fast mode's indirect light): camera cuts.
  void reset_view_history();
  // True when the final view resolves with temporal upsampling (scale < 1 or following time).
  bool upsampling() const;
  // (Re)allocates the buffers at the render size when it changes.
  void resize_render(uint32_t width, uint32_t height);

  const rp::cl::Context& context_;
  rp::cl::ProgramCache& programs_;  // kernels built after construction (set_prt)
  RenderSettings settings_;
  rp::cl::Profiler profiler_;
  std::unique_ptr<GpuScene> scene_;
  std::unique_ptr<passes::VisibilityPass> visibility_;         // also draws the shadow map
  std::unique_ptr<passes::EmbreeVisibilityPass> embree_;      // set with VisibilityBackend::kEmbree
  std::unique_ptr<passes::GBufferPass> gbuffer_pass_;
  std::unique_ptr<passes::VoxelizePass> voxelize_;
  std::unique_ptr<passes::VoxelMipsPass> voxel_mips_;
  std::unique_ptr<passes::BouncePass> bounce_;  // only with settings_.bounces >= 2
  std::unique_ptr<passes::IndirectPass> indirect_;  // set with Quality::kFast
  std::unique_ptr<passes::LightPass> light_;
  std::unique_ptr<passes::PunctualLightPass> punctual_;  // a file scene's lights
  std::unique_ptr<passes::SkyBackgroundPass> sky_background_;  // the environment seen directly
  std::unique_ptr<passes::PrtSkyPass> prt_;  // set_prt: the sky's diffuse light by PRT
  bool lamp_map_drawn_ = false;  // the lamp's shadow map holds a drawing (see render())
  SetupTimes setup_times_;
  std::unique_ptr<passes::ShadowFilterPass> shadow_filter_;  // the mips pcss / vssm read
  std::unique_ptr<passes::ToneMapPass> tone_map_;
  std::unique_ptr<passes::TaaPass> taa_;
  std::unique_ptr<passes::TaaUpsamplePass> taa_upsample_;
  std::unique_ptr<passes::BloomPass> bloom_;
  std::unique_ptr<passes::MotionBlurPass> motion_blur_;
  std::unique_ptr<passes::DebugViewPass> debug_view_pass_;
  passes::DebugViewSettings view_;
  // Allocates light_components_ when the view or keep_components_ needs them and they do not
  // exist at the current size; drops them otherwise.
  void update_light_components();

  passes::LightComponents light_components_;  // set only while a direct/indirect view is on
                                              // or keep_components_
  bool keep_components_ = false;
  size_t components_pixels_ = 0;     // pixels light_components_ was allocated for
  bool components_written_ = false;  // the last frame wrote light_components_
  VisibilityBuffer vis_;
  ShadowMap shadow_;
  GBuffer gbuffer_;
  VoxelVolume voxels_;                  // kDense
  SvoVolume svo_;                       // kSvo
  std::unique_ptr<passes::SvoPass> svo_pass_;  // kSvo
  StillVolume still_volume_;  // whether the GI volume's inputs changed (build_voxels)
  ::cl::Buffer hdr_;    // float4 per pixel: the light pass's output
  // The reference mode's screen-space reflections: the previous frame's hdr_, copied
  // before the light pass overwrites it (float4 per pixel; not allocated in the fast mode, whose
  // indirect pass reads hdr_ before the light pass), and whether it holds that frame (not after
  // a start, resize, reset or camera cut).
  ::cl::Buffer hdr_prev_;
  bool hdr_prev_valid_ = false;
  ::cl::Buffer post_[2];  // float4 per output pixel: post-processing ping-pong
  uint32_t render_width_ = 0, render_height_ = 0;  // the size of vis_, gbuffer_, hdr_, ...
  std::optional<glm::mat4> last_view_;  // camera of the previous frame (camera-cut detection)
  ::cl::Buffer rgba8_;  // uint per pixel
};

}  // namespace rp::render
