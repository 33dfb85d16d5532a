// libFuzzer target: the record/replay log parser as `--replay` runs it (app::parse_replay_text:
// scene::parse_input_log after the NUL check) and its writer.
//
// Findings are crashes, sanitizer reports, leaks, hangs, and these broken properties:
// - malformed input throws scene::InputLogError (any other exception escapes and aborts) whose
//   line() is a line of the input (1..lines; "empty file" is line 1), whose message starts
//   with the file name, and which, as shown to the user (app::printable), is one line of at most
//   3000 bytes without control bytes, however long or binary the log's words;
// - whatever parses is writable (write_input_log does not reject it) and the written log parses
//   back to bit-identical events (floats compared by bits, so -0 vs 0 would show), and writing
//   those again gives the same text.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "app/printable.h"
#include "app/replay_text.h"
#include "scene/input.h"

namespace {

using rp::scene::InputEvent;

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "fuzz_input_log: %s\n", what);
  std::abort();
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool identical(const InputEvent& a, const InputEvent& b) {
  return a.step == b.step && a.type == b.type && a.key == b.key && same_bits(a.cursor.x, b.cursor.x) &&
         same_bits(a.cursor.y, b.cursor.y) && same_bits(a.viewport.x, b.viewport.x) &&
         same_bits(a.viewport.y, b.viewport.y);
}

// Lines as std::getline sees them: a last line without '\n' still counts.
size_t count_lines(const std::string& text) {
  size_t lines = 0;
  for (char c : text) lines += c == '\n';
  if (!text.empty() && text.back() != '\n') ++lines;
  return lines;
}

std::string write(const std::vector<InputEvent>& events) {
  std::ostringstream out;
  try {
    rp::scene::write_input_log(out, events);
  } catch (const rp::scene::InputLogError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    finding("the parser accepted an event the writer rejects");
  }
  return out.str();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string name = "fuzz.txt";
  std::vector<InputEvent> events;
  try {
    events = rp::app::parse_replay_text(text, name);
  } catch (const rp::scene::InputLogError& e) {
    const size_t lines = count_lines(text);
    if (e.line() < 1 || e.line() > (lines > 0 ? lines : 1)) finding("error names a line outside the input");
    if (std::string(e.what()).rfind(name + ":", 0) != 0) finding("error message does not start with the file name");
    const std::string shown = rp::app::printable(e.what());
    if (shown.size() > 3000) finding("the message shown is longer than 3000 bytes");
    for (const char c : shown)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) finding("control byte in the message shown");
    return 0;
  }

  const std::string written = write(events);
  std::vector<InputEvent> reread;
  try {
    std::istringstream in(written);
    reread = rp::scene::parse_input_log(in, "<written>");
  } catch (const rp::scene::InputLogError& e) {
    std::fprintf(stderr, "%s\n--- written ---\n%s", e.what(), written.c_str());
    finding("a written log does not parse");
  }
  if (reread.size() != events.size()) finding("round trip changed the event count");
  for (size_t i = 0; i < events.size(); ++i)
    if (!identical(events[i], reread[i])) finding("round trip changed an event");
  if (write(reread) != written) finding("writing the re-read events gave different text");
  return 0;
}
