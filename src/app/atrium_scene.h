// `--scene atrium`: the generated courtyard (scene/atrium.h), written once as a glTF file into
// the user's cache and then opened like any scene file, so every command (render, run, bench,
// the accuracy report) loads it through the same glTF loader and records the file's path and
// content hash.
#pragma once

#include <filesystem>
#include <string>

namespace rp::app {

inline constexpr const char* kAtriumScene = "atrium";
inline bool is_atrium_scene(const std::string& scene) { return scene == kAtriumScene; }

// The scenes folder beside the truth cache (default_truth_cache_dir's parent / "scenes"),
// the file named by scene::kAtriumVersion: "<cache>/rolypoly/scenes/atrium-1.glb".
std::filesystem::path atrium_cache_file();

// atrium_cache_file(), generated first when it is not there (a few seconds; one line on
// stderr says so). The file appears whole or not at all (io::write_file), so processes that
// generate it at once each leave a complete copy. Throws io::WriteError when the folder or file
// cannot be written.
std::filesystem::path atrium_scene_file();

}  // namespace rp::app
