// Input events stamped with the simulation step they apply at, and their record/replay log, so
// a headless render reproduces an interactive session frame for frame.
//
// Log format (text, one event per line, '#' comments and blank lines ignored):
//   rolypoly-input 1
//   step 120 key S
//   step 125 key Space
//   step 130 mouse_down 312.5 200 720 720      cursor x y, viewport width height (pixels)
//   step 131 mouse_move 318.25 204.5 720 720
//   step 140 mouse_up 320 210 720 720
//   step 144 frame                             a frame was shown after the world reached step 144
// Steps never decrease; several events may share a step (they apply in file order). Floats are
// written in the shortest form that reads back bit-identical (std::to_chars), read with
// std::from_chars (locale independent).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace rp::scene {

// Keys are stored as one char: 'A'-'Z' and '0'-'9' as themselves, ' ' for the space bar (written
// "Space"). New toggles (render debug views...) need no format change.
namespace keys {
inline constexpr char kMotionBlur = 'M';
inline constexpr char kMarbles = 'S';
inline constexpr char kFireball = 'F';
inline constexpr char kPause = 'P';
inline constexpr char kReset = 'R';
inline constexpr char kSingleStep = ' ';  // while paused
inline constexpr char kTaa = 'T';         // render toggles: carried in the log like the rest
inline constexpr char kBloom = 'B';
}  // namespace keys

// True for the chars a key event may carry.
bool is_valid_key(char key);

// Frame marks a displayed frame: the interactive loop advanced the world to `step`, then rendered.
// Wall-clock time decides how many steps a frame takes, so a replay follows these marks to
// reproduce an interactive session frame for frame.
enum class InputEventType : uint8_t { Key, MouseDown, MouseUp, MouseMove, Frame };

// One event. Mouse events are the left button (the only one that drags). Cursor positions are
// continuous window pixels, (0,0) the top-left corner, y down (as picking.h's camera_ray takes
// them); the viewport size is stored with each so a replay at another size maps the same NDC.
struct InputEvent {
  uint64_t step = 0;          // simulation step counter value at which the event applies
  InputEventType type = InputEventType::Key;
  char key = 0;               // Key events only (0 otherwise)
  glm::vec2 cursor{0.0f};     // mouse events only
  glm::vec2 viewport{0.0f};   // mouse events only, both > 0

  static InputEvent key_press(uint64_t step, char key);
  static InputEvent frame(uint64_t step);
  static InputEvent mouse(uint64_t step, InputEventType type, glm::vec2 cursor, glm::vec2 viewport);

  // The cursor in another viewport at the same NDC position.
  glm::vec2 cursor_in(glm::vec2 other_viewport) const { return cursor / viewport * other_viewport; }

  bool operator==(const InputEvent&) const = default;
};

// A malformed log or an unreadable/unwritable file: the message names the file, the line (when
// there is one) and what is wrong, e.g. "session.txt:7: unknown event 'mouse_drag'".
class InputLogError : public std::runtime_error {
 public:
  InputLogError(const std::string& name, size_t line, const std::string& what);
  size_t line() const { return line_; }  // 1-based; 0 when the error concerns the whole file

 private:
  size_t line_;
};

inline constexpr int kInputLogVersion = 1;

// The largest step a log may name: 2^31 - 1, about 103 days of simulation at 240 steps per
// second. Larger steps are errors when read, not truncated (the world advances by int counts:
// step 4294967300 used to replay as step 4).
inline constexpr uint64_t kMaxInputStep = (uint64_t(1) << 31) - 1;

// Writes the header and one line per event. Throws InputLogError (line 0, name "<stream>") for an
// event that could not be read back: invalid key, non-finite or non-positive viewport, steps
// going backwards.
void write_input_log(std::ostream& out, const std::vector<InputEvent>& events);
// Parses a whole log; `name` is used in error messages (the file name). Steps above
// kMaxInputStep are errors.
std::vector<InputEvent> parse_input_log(std::istream& in, const std::string& name);

// File versions of the two above (errors name the path).
void write_input_log_file(const std::string& path, const std::vector<InputEvent>& events);
std::vector<InputEvent> read_input_log_file(const std::string& path);

// Collects events during an interactive session.
class InputRecorder {
 public:
  // Throws std::invalid_argument if the event's step is before the last recorded one.
  void record(const InputEvent& event);
  const std::vector<InputEvent>& events() const { return events_; }
  void write(std::ostream& out) const { write_input_log(out, events_); }

 private:
  std::vector<InputEvent> events_;
};

// Hands out recorded events in order. due(step) returns every event not handed out yet whose
// step is <= `step` (so a caller that skipped a step still gets them, in order), and never hands
// an event out twice.
class InputReplayer {
 public:
  InputReplayer() = default;
  // Throws std::invalid_argument if steps decrease.
  explicit InputReplayer(std::vector<InputEvent> events);

  std::span<const InputEvent> due(uint64_t step);
  bool finished() const { return next_ == events_.size(); }
  // Step of the last event (0 when empty): a replay should run at least this far.
  uint64_t last_step() const { return events_.empty() ? 0 : events_.back().step; }
  const std::vector<InputEvent>& events() const { return events_; }

 private:
  std::vector<InputEvent> events_;
  size_t next_ = 0;
};

}  // namespace rp::scene
