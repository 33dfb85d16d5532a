// Input event log: exact text format, bit-exact round trip, one clear error per malformed line,
// recorder and replayer.
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "scene/input.h"
#include "scene/random.h"

namespace {

using rp::scene::InputEvent;
using rp::scene::InputEventType;
using rp::scene::InputLogError;
using rp::scene::InputRecorder;
using rp::scene::InputReplayer;

std::string to_text(const std::vector<InputEvent>& events) {
  std::ostringstream out;
  rp::scene::write_input_log(out, events);
  return out.str();
}

std::vector<InputEvent> from_text(const std::string& text, const std::string& name = "test.log") {
  std::istringstream in(text);
  return rp::scene::parse_input_log(in, name);
}

uint32_t bits(float v) {
  uint32_t b = 0;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

void expect_bit_identical(const InputEvent& a, const InputEvent& b, size_t i) {
  EXPECT_EQ(a.step, b.step) << "event " << i;
  EXPECT_EQ(a.type, b.type) << "event " << i;
  EXPECT_EQ(a.key, b.key) << "event " << i;
  EXPECT_EQ(bits(a.cursor.x), bits(b.cursor.x)) << "event " << i;
  EXPECT_EQ(bits(a.cursor.y), bits(b.cursor.y)) << "event " << i;
  EXPECT_EQ(bits(a.viewport.x), bits(b.viewport.x)) << "event " << i;
  EXPECT_EQ(bits(a.viewport.y), bits(b.viewport.y)) << "event " << i;
}

TEST(InputLog, WritesTheDocumentedFormat) {
  const std::vector<InputEvent> events = {
      InputEvent::key_press(120, rp::scene::keys::kMarbles),
      InputEvent::key_press(125, rp::scene::keys::kSingleStep),
      InputEvent::mouse(130, InputEventType::MouseDown, {312.5f, 200.0f}, {720.0f, 720.0f}),
      InputEvent::mouse(130, InputEventType::MouseMove, {318.25f, -4.5f}, {720.0f, 720.0f}),
      InputEvent::mouse(140, InputEventType::MouseUp, {320.0f, 210.0f}, {1280.0f, 720.0f}),
      InputEvent::frame(144),
  };
  EXPECT_EQ(to_text(events),
            "rolypoly-input 1\n"
            "step 120 key S\n"
            "step 125 key Space\n"
            "step 130 mouse_down 312.5 200 720 720\n"
            "step 130 mouse_move 318.25 -4.5 720 720\n"
            "step 140 mouse_up 320 210 1280 720\n"
            "step 144 frame\n");
  EXPECT_EQ(from_text(to_text(events)), events);
}

TEST(InputLog, RoundTripIsBitExact) {
  std::vector<InputEvent> events;
  uint64_t step = 0;
  for (char k = 'A'; k <= 'Z'; ++k) events.push_back(InputEvent::key_press(step++, k));
  for (char k = '0'; k <= '9'; ++k) events.push_back(InputEvent::key_press(step, k));  // same step
  events.push_back(InputEvent::key_press(step, ' '));
  // Awkward floats: not exactly decimal, subnormal, negative zero, extremes, neighbours.
  const float awkward[] = {0.1f, 1.0f / 3.0f, 1e-40f, -0.0f, FLT_MAX, FLT_MIN, -FLT_MAX,
                           std::nextafter(720.0f, 1e9f), std::nextafter(0.5f, 0.0f), 123456.789f};
  for (float a : awkward) {
    events.push_back(InputEvent::mouse(++step, InputEventType::MouseMove, {a, -a}, {720.0f, 720.0f}));
    if (a > 0.0f) events.push_back(InputEvent::mouse(step, InputEventType::MouseDown, {1.0f, 2.0f}, {a, a}));
  }
  // Random finite bit patterns.
  rp::scene::Rng rng(99);
  while (events.size() < 2000) {
    float v[4];
    for (float& f : v) {
      do {
        const uint32_t b = rng.next_u32();
        std::memcpy(&f, &b, sizeof f);
      } while (!std::isfinite(f));
    }
    const auto type = static_cast<InputEventType>(1 + rng.next_u32() % 3);
    events.push_back(InputEvent::mouse(step, type, {v[0], v[1]}, {std::abs(v[2]) + 1.0f, std::abs(v[3]) + 1.0f}));
    step += rng.next_u32() % 3;
  }
  events.push_back(InputEvent::key_press(rp::scene::kMaxInputStep, 'R'));  // the largest step

  const std::string text = to_text(events);
  const std::vector<InputEvent> back = from_text(text);
  ASSERT_EQ(back.size(), events.size());
  for (size_t i = 0; i < events.size(); ++i) expect_bit_identical(back[i], events[i], i);
  EXPECT_EQ(to_text(back), text);  // and it writes the same text again
}

TEST(InputLog, AcceptsCommentsBlankLinesAndCrlf) {
  const auto events = from_text(
      "rolypoly-input 1\r\n"
      "# recorded by hand\r\n"
      "\r\n"
      "   step 3   key   F  \r\n"
      "step 4 mouse_down 1e2 2.5e-1 640 480\r\n");
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0], InputEvent::key_press(3, 'F'));
  EXPECT_EQ(events[1], InputEvent::mouse(4, InputEventType::MouseDown, {100.0f, 0.25f}, {640.0f, 480.0f}));
  EXPECT_TRUE(from_text("rolypoly-input 1\n").empty());
}

struct BadCase {
  const char* text;
  size_t line;
  const char* message;  // a part of the error message
};

TEST(InputLog, EachMalformedLineNamesFileLineAndProblem) {
  const std::string h = "rolypoly-input 1\n";
  const BadCase cases[] = {
      {"", 1, "header"},
      {"hello 1\n", 1, "header"},
      {"rolypoly-input\n", 1, "header"},
      {"rolypoly-input 2\n", 1, "version '2'"},
      {"step 1 key S\n", 1, "header"},
  };
  const std::vector<BadCase> body = {
      {"step 1 jump\n", 2, "unknown event 'jump'"},
      {"stop 1 key S\n", 2, "expected 'step"},
      {"step\n", 2, "missing fields"},
      {"step 1\n", 2, "missing fields"},
      {"step 1 key\n", 2, "missing fields"},
      {"step 1 key S M\n", 2, "extra fields"},
      {"step 1 frame 3\n", 2, "extra fields"},
      {"step x key S\n", 2, "step number"},
      {"step -1 key S\n", 2, "step number"},
      {"step 1.5 key S\n", 2, "step number"},
      {"step 99999999999999999999 key S\n", 2, "step 99999999999999999999 is out of range"},
      // Steps the world cannot count to (int) are errors, not truncated (this one
      // used to replay as step 4).
      {"step 4294967300 frame\n", 2, "step 4294967300 is out of range: steps go up to 2147483647"},
      {"step 2147483648 key S\n", 2, "out of range"},
      {"step 1 key s\n", 2, "invalid key 's'"},
      {"step 1 key Enter\n", 2, "invalid key 'Enter'"},
      {"step 1 mouse_down 1 2 720\n", 2, "missing fields"},
      {"step 1 mouse_down 1 2 720 720 5\n", 2, "extra fields"},
      {"step 1 mouse_move abc 2 720 720\n", 2, "cursor x must be a number"},
      {"step 1 mouse_move 1 2.5x 720 720\n", 2, "cursor y must be a number"},
      {"step 1 mouse_move 1 2 +720 720\n", 2, "viewport width must be a number"},
      {"step 1 mouse_move nan 2 720 720\n", 2, "finite"},
      {"step 1 mouse_move 1 inf 720 720\n", 2, "finite"},
      {"step 1 mouse_move 1 2 720 -inf\n", 2, "finite"},
      {"step 1 mouse_up 1e60 2 720 720\n", 2, "out of range"},
      {"step 1 mouse_up 1 2 0 720\n", 2, "positive"},
      {"step 1 mouse_up 1 2 720 -720\n", 2, "positive"},
      {"step 5 key S\n# fine\nstep 4 key M\n", 4, "goes backwards"},
  };
  std::vector<BadCase> all(std::begin(cases), std::end(cases));
  std::vector<std::string> texts;
  for (const BadCase& c : all) texts.push_back(c.text);
  for (const BadCase& c : body) {
    all.push_back(c);
    texts.push_back(h + c.text);
  }
  for (size_t i = 0; i < all.size(); ++i) {
    try {
      from_text(texts[i], "session.txt");
      ADD_FAILURE() << "no error for: " << texts[i];
    } catch (const InputLogError& e) {
      const std::string what = e.what();
      EXPECT_EQ(e.line(), all[i].line) << what;
      EXPECT_EQ(what.rfind("session.txt:" + std::to_string(all[i].line) + ": ", 0), 0u) << what;
      EXPECT_NE(what.find(all[i].message), std::string::npos) << "'" << what << "' lacks '" << all[i].message << "'";
    }
  }
}

TEST(InputLog, WriterRejectsEventsItCouldNotReadBack) {
  EXPECT_THROW(to_text({InputEvent::key_press(1, 'x')}), InputLogError);
  EXPECT_THROW(to_text({InputEvent::key_press(1, '\n')}), InputLogError);
  EXPECT_THROW(to_text({InputEvent::mouse(1, InputEventType::MouseMove, {1.0f, 2.0f}, {0.0f, 720.0f})}),
               InputLogError);
  EXPECT_THROW(to_text({InputEvent::mouse(1, InputEventType::MouseMove, {NAN, 2.0f}, {720.0f, 720.0f})}),
               InputLogError);
  EXPECT_THROW(to_text({InputEvent::key_press(2, 'S'), InputEvent::key_press(1, 'S')}), InputLogError);
  EXPECT_THROW(to_text({InputEvent::frame(rp::scene::kMaxInputStep + 1)}), InputLogError);
}

TEST(InputLog, FilesRoundTripAndMissingFilesAreNamed) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("rolypoly_input_test_" + std::to_string(::getpid()) + ".txt");
  const std::vector<InputEvent> events = {InputEvent::key_press(0, 'F'),
                                          InputEvent::mouse(7, InputEventType::MouseDown, {0.1f, 0.2f}, {3.0f, 4.0f})};
  rp::scene::write_input_log_file(path.string(), events);
  const auto back = rp::scene::read_input_log_file(path.string());
  std::filesystem::remove(path);
  ASSERT_EQ(back.size(), 2u);
  for (size_t i = 0; i < 2; ++i) expect_bit_identical(back[i], events[i], i);
  try {
    rp::scene::read_input_log_file(path.string());
    ADD_FAILURE() << "no error for a missing file";
  } catch (const InputLogError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

TEST(InputEvent, CursorMapsToTheSameNdcInAnotherViewport) {
  const InputEvent e = InputEvent::mouse(0, InputEventType::MouseMove, {360.0f, 180.0f}, {720.0f, 720.0f});
  const glm::vec2 c = e.cursor_in({1440.0f, 360.0f});
  EXPECT_FLOAT_EQ(c.x, 720.0f);
  EXPECT_FLOAT_EQ(c.y, 90.0f);
}

TEST(InputRecorder, CollectsInOrderAndRejectsGoingBack) {
  InputRecorder rec;
  rec.record(InputEvent::key_press(3, 'M'));
  rec.record(InputEvent::key_press(3, 'P'));
  rec.record(InputEvent::mouse(9, InputEventType::MouseDown, {1.0f, 2.0f}, {10.0f, 10.0f}));
  EXPECT_THROW(rec.record(InputEvent::key_press(8, 'R')), std::invalid_argument);
  ASSERT_EQ(rec.events().size(), 3u);
  std::ostringstream out;
  rec.write(out);
  EXPECT_EQ(out.str(), "rolypoly-input 1\nstep 3 key M\nstep 3 key P\nstep 9 mouse_down 1 2 10 10\n");
}

TEST(InputReplayer, HandsOutDueEventsInOrderOnce) {
  const std::vector<InputEvent> events = {InputEvent::key_press(0, 'S'), InputEvent::key_press(2, 'F'),
                                          InputEvent::key_press(2, 'M'), InputEvent::key_press(5, 'P'),
                                          InputEvent::key_press(9, 'R')};
  InputReplayer rp(events);
  EXPECT_EQ(rp.last_step(), 9u);
  auto due0 = rp.due(0);
  ASSERT_EQ(due0.size(), 1u);
  EXPECT_EQ(due0[0].key, 'S');
  EXPECT_TRUE(rp.due(0).empty());  // never twice
  EXPECT_TRUE(rp.due(1).empty());
  auto due2 = rp.due(2);
  ASSERT_EQ(due2.size(), 2u);
  EXPECT_EQ(due2[0].key, 'F');
  EXPECT_EQ(due2[1].key, 'M');
  auto due7 = rp.due(7);  // step 5 was skipped by the caller: still handed out
  ASSERT_EQ(due7.size(), 1u);
  EXPECT_EQ(due7[0].key, 'P');
  EXPECT_FALSE(rp.finished());
  auto due100 = rp.due(100);
  ASSERT_EQ(due100.size(), 1u);
  EXPECT_EQ(due100[0].key, 'R');
  EXPECT_TRUE(rp.finished());
  EXPECT_THROW(InputReplayer({InputEvent::key_press(2, 'S'), InputEvent::key_press(1, 'S')}),
               std::invalid_argument);
  EXPECT_TRUE(InputReplayer().finished());
}

}  // namespace
