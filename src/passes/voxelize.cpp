#include "passes/voxelize.h"

#include <string>

#include "cl/error.h"

namespace rp::passes {
namespace {

constexpr size_t kGroup = 64;  // 1D work-groups for every voxelize kernel

// The fixed-point format of render/voxel_volume.h, handed to the kernels (one definition).
std::string fixed_point_options() {
  return "-DRP_VOXEL_FIXED_BITS=" + std::to_string(render::kVoxelFixedBits) +
         " -DRP_VOXEL_MAX_CONTRIB=" + std::to_string(render::kVoxelMaxContribution) + "f" +
         " -DRP_VOXEL_SATURATED=" + std::to_string(render::kVoxelSaturatedSum) + "f";
}

}  // namespace

VoxelizePass::VoxelizePass(const rp::cl::Context& /*context*/, rp::cl::ProgramCache& programs) {
  const std::string options = fixed_point_options();
  clear_ = programs.kernel("voxelize.cl", "voxelize_clear", options);
  triangles_ = programs.kernel("voxelize.cl", "voxelize_triangles", options);
  spheres_ = programs.kernel("voxelize.cl", "voxelize_spheres", options);
  resolve_ = programs.kernel("voxelize.cl", "voxelize_resolve", options);
}

void VoxelizePass::run(rp::cl::Profiler& profiler, const render::GpuScene& scene,
                       const render::ShadowMap& shadow, render::VoxelVolume& volume) {
  const cl_uint r = volume.resolution;
  if (!render::VoxelVolume::valid_resolution(r) || volume.chain() == nullptr)
    throw rp::cl::Error("voxelize pass: the voxel volume has not been allocated (resize it)");
  if (scene.constants.voxel_resolution != r || scene.constants.voxel_levels != volume.levels)
    throw rp::cl::Error("voxelize pass: the volume is " + std::to_string(r) + "^3 with " +
                        std::to_string(volume.levels) + " levels but the frame constants say " +
                        std::to_string(scene.constants.voxel_resolution) + "^3 with " +
                        std::to_string(scene.constants.voxel_levels) + " levels");
  if (shadow.size != scene.constants.shadow_size)
    throw rp::cl::Error("voxelize pass: shadow map is " + std::to_string(shadow.size) +
                        " texels wide but the frame constants say " +
                        std::to_string(scene.constants.shadow_size));
  const cl_uint voxels = r * r * r;

  clear_.setArg(0, volume.accum);
  clear_.setArg(1, volume.overflow);
  clear_.setArg(2, voxels);
  profiler.enqueue("voxelize", clear_, ::cl::NDRange(rp::cl::round_up(voxels, kGroup)),
                   ::cl::NDRange(kGroup));

  if (scene.instance_triangle_count > 0) {
    cl_uint arg = 0;
    triangles_.setArg(arg++, scene.frame);
    triangles_.setArg(arg++, scene.instances);
    triangles_.setArg(arg++, cl_uint(scene.instance_count));
    triangles_.setArg(arg++, cl_uint(scene.instance_triangle_count));
    triangles_.setArg(arg++, scene.vertices);
    triangles_.setArg(arg++, scene.triangles);
    triangles_.setArg(arg++, scene.materials);
    triangles_.setArg(arg++, scene.textures);
    triangles_.setArg(arg++, scene.texels);
    triangles_.setArg(arg++, shadow.depth);
    triangles_.setArg(arg++, r);
    triangles_.setArg(arg++, volume.accum);
    triangles_.setArg(arg++, volume.overflow);
    profiler.enqueue("voxelize", triangles_,
                     ::cl::NDRange(rp::cl::round_up(scene.instance_triangle_count, kGroup)),
                     ::cl::NDRange(kGroup));
  }

  if (scene.sphere_count > 0) {
    cl_uint arg = 0;
    spheres_.setArg(arg++, scene.frame);
    spheres_.setArg(arg++, scene.spheres);
    spheres_.setArg(arg++, cl_uint(scene.sphere_count));
    spheres_.setArg(arg++, shadow.depth);
    spheres_.setArg(arg++, r);
    spheres_.setArg(arg++, volume.accum);
    spheres_.setArg(arg++, volume.overflow);
    profiler.enqueue("voxelize", spheres_,
                     ::cl::NDRange(rp::cl::round_up(scene.sphere_count, kGroup)),
                     ::cl::NDRange(kGroup));
  }

  resolve_.setArg(0, volume.accum);
  resolve_.setArg(1, volume.overflow);
  resolve_.setArg(2, volume.chain);
  resolve_.setArg(3, voxels);
  profiler.enqueue("voxelize", resolve_, ::cl::NDRange(rp::cl::round_up(voxels, kGroup)),
                   ::cl::NDRange(kGroup));
}

}  // namespace rp::passes
