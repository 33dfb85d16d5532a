// PoCL's kernel cache folder: which one, what to do when it is unusable, and PoCL's debris.
//
// PoCL compiles each kernel once and keeps the result under POCL_CACHE_DIR (default
// ~/.cache/pocl/kcache). When that folder cannot be created or written (HOME=/nonexistent, a
// read-only cache, a path under a file), PoCL's device initialisation fails and the ICD loader
// reports platforms without devices: "OpenCL platforms were found but none has a device", a
// message that hides the cause. POCL_CACHE_DIR set but empty makes PoCL abort on an assertion
// (exit 134). And PoCL's initialisation leaves an empty "tempfile_XXXXXX" (its writability
// probe, never removed) in the folder on every run.
#pragma once

#include <string>

namespace rp::cl {

// Before the first OpenCL call: chooses the cache folder and exports it as POCL_CACHE_DIR.
// POCL_CACHE_DIR as the user set it, else a persistent per-user folder
// ($XDG_CACHE_HOME/rolypoly/pocl or ~/.cache/rolypoly/pocl); empty counts as unset. The folder
// is created and a file is created in it and removed again; when that fails, a private
// temporary folder (removed at exit) is used instead, with a one-line warning on stderr that
// names the folder and the reason. Returns the folder in use ("" if even that failed).
std::string ensure_pocl_cache_dir();

// After PoCL's initialisation (the first platform query): removes its empty writability-probe
// files from the cache folder, those of this process and stale ones (older than 10 minutes)
// of earlier runs. Cheap after the first call (does nothing).
void remove_pocl_probe_files();

}  // namespace rp::cl
