// PRT transfer vectors cached on disk: a 10k-vertex scene at 512 directions per
// vertex takes seconds to minutes, a restart should take milliseconds. The pattern of the path
// tracer's truth cache (app/truth_cache.h), with a binary file since the payload is float arrays.
//
// Key: 64-bit FNV-1a (io/fnv1a.h) of everything the transfer depends on: kPrtVersion; the
// settings (bands, kind, bounces for kInterreflected, samples and glow cells for the traced
// kinds, the suns' directions for kInterreflected with bounces; not threads: the result does not
// depend on them); the meshes (positions, normals, uvs, triangles, per triangle materials); the
// materials' albedo, base-colour texture and alpha mask (the hit albedo and the holes); the
// textures' texels and sampling; and each frame instance's mesh and model matrix. Not the
// camera, spheres, environment or lights (but the suns' directions and the glow): PRT is
// independent of the lighting otherwise.
//
// File: <dir>/prt-<key>.bin, written atomically (io/atomic_file.h), host byte order (a cache
// belongs to its machine):
//   char[8]  "RPPRTBIN"
//   u32      length, then the version string (kPrtVersion)
//   char[16] the key, as hex
//   u32 x 9  bands, kind, bounces, samples, channels, vertex count, instance count, sun count,
//            glow cell count
//   u32 x 2  per instance: first vertex, vertex count
//   f32 x 3  per vertex: world position; then f32 x 3 per vertex: world normal
//   f32      coefficients, vertex count * channels * bands^2 (PrtTransfer's layout)
//   f32      interreflected with bounces only: the shadowed transfer, vertex count * bands^2
//   f32 x 3  per sun: its direction; then f32, vertex count * suns * 3: the suns' bounces
//   f32 x 6  per glow cell: direction, irradiance; then, with cells, f32 x 3 per vertex: glow
//   u64      FNV-1a of every byte before it
// Read back only when the size is exactly that, the magic, version, key and settings match and
// the checksum holds; anything else (truncated, corrupt, older version) is ignored and rebuilt.
#pragma once

#include <atomic>
#include <filesystem>
#include <optional>
#include <string>

#include "scene/frame_scene.h"
#include "truth/prt_transfer.h"

namespace rp::truth {

// Bump when the transfer changes for the same inputs (a fix, a new convention).
inline constexpr const char* kPrtVersion = "rolypoly-prt/4";

// The cache key above, as 16 hex digits.
std::string prt_key(const scene::SceneAssets& assets, const scene::FrameScene& frame,
                    const PrtSettings& settings);

// $XDG_CACHE_HOME/rolypoly/prt, else $HOME/.cache/rolypoly/prt, else ./.rolypoly-cache/prt: the
// truth cache's root (app/truth_cache.h) with "prt" for "truth".
std::filesystem::path default_prt_cache_dir();

// The file of `key` in `dir`.
std::filesystem::path prt_cache_file(const std::filesystem::path& dir, const std::string& key);

// Writes `transfer` as the entry of `key` (creating `path`'s folder). Throws io::WriteError or
// std::filesystem::filesystem_error when it cannot.
void write_prt_file(const std::filesystem::path& path, const std::string& key,
                    const PrtTransfer& transfer);

// The entry at `path` when it is complete and made for `key` and `settings`; std::nullopt for a
// missing, truncated, corrupt or mismatched file (never throws for a bad file).
std::optional<PrtTransfer> read_prt_file(const std::filesystem::path& path,
                                         const std::string& key, const PrtSettings& settings);

struct CachedPrt {
  PrtTransfer transfer;
  bool from_cache = false;
  std::filesystem::path file;
};

// The cached entry when there is a valid one, else computes it (compute_prt_transfer, progress
// and cancel passed on) and stores it. A cache that cannot be written is reported on stderr and
// the transfer still returned; a corrupt entry is computed anew and replaced.
CachedPrt cached_prt_transfer(const scene::SceneAssets& assets, const scene::FrameScene& frame,
                              const PrtSettings& settings, const std::filesystem::path& dir,
                              const PrtProgressFn& progress = {},
                              const std::atomic<bool>* cancel = nullptr);

}  // namespace rp::truth
