#include "scene/input.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <istream>
#include <ostream>
#include <sstream>

#include "io/atomic_file.h"
#include "io/output_path.h"

namespace rp::scene {

namespace {

constexpr const char* kHeaderWord = "rolypoly-input";

const char* type_word(InputEventType type) {
  switch (type) {
    case InputEventType::Key: return "key";
    case InputEventType::MouseDown: return "mouse_down";
    case InputEventType::MouseUp: return "mouse_up";
    case InputEventType::MouseMove: return "mouse_move";
    case InputEventType::Frame: return "frame";
  }
  return "?";
}

std::string key_word(char key) { return key == ' ' ? std::string("Space") : std::string(1, key); }

std::vector<std::string> split_words(const std::string& line) {
  std::vector<std::string> words;
  std::istringstream stream(line);
  std::string word;
  while (stream >> word) words.push_back(word);
  return words;
}

// Shortest decimal form that reads back to the same float bits.
std::string format_float(float v) {
  char buf[32];
  const auto result = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, result.ptr);
}

// Validates what the format can hold; returns "" or what is wrong.
std::string event_problem(const InputEvent& e) {
  if (e.type == InputEventType::Key) {
    if (!is_valid_key(e.key)) return "invalid key code " + std::to_string(static_cast<int>(e.key));
    return "";
  }
  if (e.type == InputEventType::Frame) return "";
  if (!std::isfinite(e.cursor.x) || !std::isfinite(e.cursor.y)) return "non-finite cursor";
  if (!std::isfinite(e.viewport.x) || !std::isfinite(e.viewport.y) || !(e.viewport.x > 0.0f) ||
      !(e.viewport.y > 0.0f)) {
    return "viewport must be finite and positive";
  }
  return "";
}

// Line parser: every failure throws InputLogError naming the file and line.
class LineParser {
 public:
  LineParser(const std::string& name, size_t line) : name_(name), line_(line) {}

  [[noreturn]] void fail(const std::string& what) const { throw InputLogError(name_, line_, what); }

  uint64_t parse_step(const std::string& word) const {
    uint64_t value = 0;
    const char* end = word.data() + word.size();
    const auto r = std::from_chars(word.data(), end, value);
    const bool digits =
        r.ptr == end && (r.ec == std::errc() || r.ec == std::errc::result_out_of_range);
    if (!digits) fail("step number must be a non-negative integer, got '" + word + "'");
    if (r.ec == std::errc::result_out_of_range || value > kMaxInputStep)
      fail("step " + word + " is out of range: steps go up to " + std::to_string(kMaxInputStep) +
           " (about 103 days at 240 steps per second)");
    return value;
  }

  float parse_float(const std::string& word, const char* what) const {
    float value = 0.0f;
    const char* end = word.data() + word.size();
    const auto r = std::from_chars(word.data(), end, value);
    if (r.ec == std::errc::result_out_of_range) fail(std::string(what) + " '" + word + "' is out of range");
    if (r.ec != std::errc() || r.ptr != end) {
      fail(std::string(what) + " must be a number, got '" + word + "'");
    }
    if (!std::isfinite(value)) fail(std::string(what) + " must be finite, got '" + word + "'");
    return value;
  }

  char parse_key(const std::string& word) const {
    if (word == "Space") return ' ';
    if (word.size() == 1 && word[0] != ' ' && is_valid_key(word[0])) return word[0];
    fail("invalid key '" + word + "' (expected A-Z, 0-9 or Space)");
  }

  void expect_fields(const std::vector<std::string>& words, size_t count, const char* usage) const {
    if (words.size() < count) fail(std::string("missing fields: expected '") + usage + "'");
    if (words.size() > count) fail(std::string("extra fields: expected '") + usage + "'");
  }

 private:
  const std::string& name_;
  size_t line_;
};

InputEvent parse_event(const LineParser& p, const std::vector<std::string>& words) {
  if (words[0] != "step") p.fail("expected 'step N <event>', got '" + words[0] + "'");
  if (words.size() < 3) p.fail("missing fields: expected 'step N <event> ...'");
  InputEvent e;
  e.step = p.parse_step(words[1]);
  const std::string& kind = words[2];
  if (kind == "key") {
    p.expect_fields(words, 4, "step N key K");
    return InputEvent::key_press(e.step, p.parse_key(words[3]));
  }
  if (kind == "frame") {
    p.expect_fields(words, 3, "step N frame");
    return InputEvent::frame(e.step);
  }
  InputEventType type;
  if (kind == "mouse_down") {
    type = InputEventType::MouseDown;
  } else if (kind == "mouse_up") {
    type = InputEventType::MouseUp;
  } else if (kind == "mouse_move") {
    type = InputEventType::MouseMove;
  } else {
    p.fail("unknown event '" + kind + "' (expected key, mouse_down, mouse_up, mouse_move or frame)");
  }
  p.expect_fields(words, 7, "step N mouse_xxx X Y WIDTH HEIGHT");
  const float x = p.parse_float(words[3], "cursor x");
  const float y = p.parse_float(words[4], "cursor y");
  const float w = p.parse_float(words[5], "viewport width");
  const float h = p.parse_float(words[6], "viewport height");
  if (!(w > 0.0f) || !(h > 0.0f)) p.fail("viewport size must be positive");
  return InputEvent::mouse(e.step, type, {x, y}, {w, h});
}

}  // namespace

bool is_valid_key(char key) {
  return key == ' ' || (key >= 'A' && key <= 'Z') || (key >= '0' && key <= '9');
}

InputEvent InputEvent::key_press(uint64_t step, char key) {
  InputEvent e;
  e.step = step;
  e.type = InputEventType::Key;
  e.key = key;
  return e;
}

InputEvent InputEvent::frame(uint64_t step) {
  InputEvent e;
  e.step = step;
  e.type = InputEventType::Frame;
  return e;
}

InputEvent InputEvent::mouse(uint64_t step, InputEventType type, glm::vec2 cursor,
                             glm::vec2 viewport) {
  InputEvent e;
  e.step = step;
  e.type = type;
  e.cursor = cursor;
  e.viewport = viewport;
  return e;
}

InputLogError::InputLogError(const std::string& name, size_t line, const std::string& what)
    : std::runtime_error(line > 0 ? name + ":" + std::to_string(line) + ": " + what
                                  : name + ": " + what),
      line_(line) {}

void write_input_log(std::ostream& out, const std::vector<InputEvent>& events) {
  out << kHeaderWord << ' ' << kInputLogVersion << '\n';
  uint64_t last_step = 0;
  for (size_t i = 0; i < events.size(); ++i) {
    const InputEvent& e = events[i];
    const std::string problem = event_problem(e);
    const std::string where = "event " + std::to_string(i);
    if (!problem.empty()) throw InputLogError("<output>", 0, where + ": " + problem);
    if (e.step < last_step) throw InputLogError("<output>", 0, where + ": step goes backwards");
    if (e.step > kMaxInputStep)
      throw InputLogError("<output>", 0, where + ": step " + std::to_string(e.step) +
                                             " is above " + std::to_string(kMaxInputStep));
    last_step = e.step;
    out << "step " << e.step << ' ' << type_word(e.type);
    if (e.type == InputEventType::Key) {
      out << ' ' << key_word(e.key);
    } else if (e.type == InputEventType::Frame) {
      // no fields
    } else {
      out << ' ' << format_float(e.cursor.x) << ' ' << format_float(e.cursor.y) << ' '
          << format_float(e.viewport.x) << ' ' << format_float(e.viewport.y);
    }
    out << '\n';
  }
}

std::vector<InputEvent> parse_input_log(std::istream& in, const std::string& name) {
  std::vector<InputEvent> events;
  std::string line;
  size_t line_number = 0;
  bool have_header = false;
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();  // CRLF files
    const LineParser p(name, line_number);
    const std::vector<std::string> words = split_words(line);
    if (!have_header) {
      if (words.size() != 2 || words[0] != kHeaderWord) {
        p.fail(std::string("expected the header '") + kHeaderWord + " " +
               std::to_string(kInputLogVersion) + "'");
      }
      if (words[1] != std::to_string(kInputLogVersion)) {
        p.fail("unsupported version '" + words[1] + "' (this build reads " +
               std::to_string(kInputLogVersion) + ")");
      }
      have_header = true;
      continue;
    }
    if (words.empty() || words[0][0] == '#') continue;
    const InputEvent e = parse_event(p, words);
    if (!events.empty() && e.step < events.back().step) {
      p.fail("step " + std::to_string(e.step) + " goes backwards (previous event at step " +
             std::to_string(events.back().step) + ")");
    }
    events.push_back(e);
  }
  if (in.bad()) throw InputLogError(name, 0, "read error");
  if (!have_header) throw InputLogError(name, 1, "empty file: expected the header");
  return events;
}

void write_input_log_file(const std::string& path, const std::vector<InputEvent>& events) {
  // Whole in memory first, then one checked write (io::write_file): a full disk is an error
  // with the system's reason, and the log is complete or absent.
  std::ostringstream out;
  write_input_log(out, events);
  try {
    io::write_file(path, out.str());
  } catch (const io::WriteError& e) {
    throw InputLogError(path, 0, "cannot write: " + e.reason());
  }
}

std::vector<InputEvent> read_input_log_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputLogError(path, 0, "cannot open for reading");
  return parse_input_log(in, path);
}

void InputRecorder::record(const InputEvent& event) {
  if (!events_.empty() && event.step < events_.back().step) {
    throw std::invalid_argument("InputRecorder: event at step " + std::to_string(event.step) +
                                " comes after step " + std::to_string(events_.back().step));
  }
  events_.push_back(event);
}

InputReplayer::InputReplayer(std::vector<InputEvent> events) : events_(std::move(events)) {
  for (size_t i = 1; i < events_.size(); ++i) {
    if (events_[i].step < events_[i - 1].step) {
      throw std::invalid_argument("InputReplayer: event " + std::to_string(i) +
                                  " goes back to step " + std::to_string(events_[i].step));
    }
  }
}

std::span<const InputEvent> InputReplayer::due(uint64_t step) {
  const size_t first = next_;
  while (next_ < events_.size() && events_[next_].step <= step) ++next_;
  return std::span<const InputEvent>(events_).subspan(first, next_ - first);
}

}  // namespace rp::scene
