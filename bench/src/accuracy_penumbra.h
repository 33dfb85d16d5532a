// The direct section's penumbra error taken apart (accuracy_direct.h): where in the picture it
// lies and how it depends on how much of the lamp the truth sees there, so that work on the
// soft shadows knows which part of the penumbra PSNR it can move.
//
// Parts of the penumbra mask (the truth's pixels with lamp_fraction in (0.05, 0.95), dilated):
//   open_floor            floor pixels whose 3x3 neighbourhood in the picture shows only floor;
//   floor_beside_objects  the other floor pixels: beside a tumbler's, marble's or wall's
//                         outline (the floor seen there may lie far behind the object);
//   objects               every other pixel of the mask (tumblers, marbles, walls).
// Each with its pixel count and direct PSNR (masked_tone_mapped_psnr; the parts' squared
// errors add up to the whole mask's). The open floor's error is also binned by the truth's lamp
// fraction at the pixel centre (tone_mapped_error_by_key, 10 bins of 0.1): the mean signed
// error says whether the real time is too dark or too bright at that depth into the penumbra,
// the RMS how far apart they are, the share how much of the open floor's error lies there.
//
// Measured on the demo at 360x360 (pcss, 512 spp; bench/results/zen3-2core-pocl-soft-shadows.md):
// the open floor 32.1 dB, the floor beside the tumblers' outlines 23.8 dB over 3 % of the mask,
// the outer penumbra (lamp fraction 0.6 to 1) about three quarters of the open floor's error,
// the real time too dark there.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rp::bench {

struct PenumbraParts {
  std::vector<uint8_t> open_floor, floor_beside_objects, objects;  // 1 byte per pixel
};

// The parts of `penumbra` (1 byte per pixel, width x height) given which pixels show the floor
// (floor_material, 1 byte per pixel). Throws std::invalid_argument on mismatched sizes.
PenumbraParts penumbra_parts(const std::vector<uint8_t>& penumbra,
                             const std::vector<uint8_t>& floor_material, uint32_t width,
                             uint32_t height);

// The breakdown of `a` (direct component, 3 floats per pixel) against `truth`:
//   {"parts": {"open_floor" | "floor_beside_objects" | "objects":
//                {"pixels": N, "direct_psnr_db": dB or null}},
//    "open_floor_by_lamp_fraction": [{"from", "to", "pixels", "mean", "rms", "share"} x 10]}
// (share: of the open floor's summed squared error; null where a bin is empty).
nlohmann::json penumbra_breakdown(const std::vector<float>& a, const std::vector<float>& truth,
                                  const PenumbraParts& parts,
                                  const std::vector<float>& lamp_fraction);

// The breakdown as the report's text lines, for shadow mode `mode`.
std::string penumbra_breakdown_text(const std::string& mode, const nlohmann::json& breakdown);

}  // namespace rp::bench
