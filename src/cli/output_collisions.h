// Outputs that would destroy each other or the command's own input, found before any work:
// `bench --json F --markdown F` used to leave only the last file written, and
// `run --replay F --record F` overwrote the log it was replaying. Paths are compared as files,
// not as strings: after following symlinks (a link to F is F), by device and inode when the
// file exists (hard links, "./F", "dir/../F"), by the resolved absolute path when it does not
// yet. Outputs written in place (character devices and FIFOs: /dev/null, /dev/stdout twice) are
// appended to, not replaced, so they never collide.
#pragma once

#include <filesystem>
#include <string>

#include "cli/cli.h"

namespace rp::cli {

// Whether writing `output` (an output option's value) would replace `other` (another output or
// an input file). False when either cannot be resolved: the usual checks report that later.
bool same_file(const std::filesystem::path& output, const std::filesystem::path& other);

// "" when every output of `command` is its own file and none is one of its inputs (--replay,
// --scene FILE); else the usage message naming both options, e.g. "--json and --markdown both
// name r.json; each output needs a file of its own".
std::string find_output_collision(const ParsedCommand& command);

}  // namespace rp::cli
