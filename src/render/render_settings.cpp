#include "render/render_settings.h"

#include <algorithm>
#include <cmath>

#include "render/voxel_volume.h"

namespace rp::render {

bool gi_resolution_supported(GiVolume volume, uint32_t resolution) {
  if (volume == GiVolume::kSvo)
    return resolution >= 2 && resolution <= 1024 && (resolution & (resolution - 1)) == 0;
  return VoxelVolume::valid_resolution(resolution);
}

uint32_t scaled_side(uint32_t output_side, float scale) {
  return std::max<uint32_t>(1, static_cast<uint32_t>(std::lround(double(output_side) * scale)));
}

}  // namespace rp::render
