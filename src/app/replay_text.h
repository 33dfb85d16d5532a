// The text of a --replay log, parsed (read_replay_log in input_file.h reads it first).
// Header-only so that fuzz/input_log_fuzzer.cpp checks this very path.
#pragma once

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "scene/input.h"

namespace rp::app {

// scene::parse_input_log, after one check of its own: a NUL byte (a binary file, not a log) is
// an InputLogError naming its line. The parser would have carried the NUL into its message, and
// the message ended there when printed.
inline std::vector<scene::InputEvent> parse_replay_text(const std::string& text,
                                                        const std::string& name) {
  if (const size_t nul = text.find('\0'); nul != std::string::npos) {
    const auto newlines = std::count(text.begin(), text.begin() + std::ptrdiff_t(nul), '\n');
    throw scene::InputLogError(name, size_t(newlines) + 1,
                               "a NUL byte: this is a binary file, not an input log");
  }
  std::istringstream in(text);
  return scene::parse_input_log(in, name);
}

}  // namespace rp::app
