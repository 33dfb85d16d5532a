// Files the user gives as input (the --replay log, the --scene file), read so that no input can
// hang the program or say the wrong thing: every failure names the file and the system's reason
// (strerror), a directory is refused as one, a FIFO or a device is read through an
// interruptible wait (SIGINT / SIGTERM stop it at once) and with a bound on its size (/dev/zero
// ends with an error, not with memory exhausted).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "scene/input.h"

namespace rp::app {

// Input logs are text of some MB (a minute of `run --record` is ~100 KB); this bound only stops
// an endless device or a wrong file.
inline constexpr size_t kMaxInputLogBytes = size_t(256) << 20;

// The whole content of `path`, at most `max_bytes`. `option` names the option in messages
// ("--replay"). Throws std::runtime_error "--replay: cannot read PATH: REASON" (No such file or
// directory, Is a directory, Permission denied, "larger than 256 MiB"), and Interrupted when a
// signal arrives while it waits for a FIFO's writer or a device's data.
std::string read_input_file(const std::string& path, const char* option, size_t max_bytes);

// --replay FILE: read_input_file, then parse_replay_text (replay_text.h).
std::vector<scene::InputEvent> read_replay_log(const std::string& path);

// --scene FILE, before the glTF loader opens it (its reads do not wait for signals): anything
// there but a regular file (or a link to one) is refused as a scene::SceneFileError (exit 2,
// like the loader's own) saying what it is.
void require_regular_file(const std::string& path, const char* option);

}  // namespace rp::app
