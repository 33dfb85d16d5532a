// User input echoed in a message (an option's value, a word of a replay log) is made safe to
// print: a 5 MB token used to be echoed whole, control characters reached the terminal as they
// are and a NUL byte ended the message where C strings end. Header-only so that the fuzzers of
// the command line and of the replay log check the very text the user sees.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>

namespace rp::app {

// A message echoing user input cut to a length that fits a terminal (the head and the tail kept,
// the middle counted), so at most about kMaxMessageBytes + 40 bytes; a quoted part ('...')
// longer than kMaxQuotedBytes is cut inside its quotes.
inline constexpr size_t kMaxMessageBytes = 600;
inline constexpr size_t kMaxQuotedBytes = 80;

namespace printable_detail {

// The length of the valid UTF-8 sequence at text[i] (0 if it is not one).
inline size_t utf8_length(std::string_view text, size_t i) {
  const auto c = static_cast<unsigned char>(text[i]);
  const size_t n = c >= 0xF0 && c <= 0xF4 ? 4 : c >= 0xE0 ? 3 : c >= 0xC2 && c < 0xE0 ? 2 : 0;
  if (n == 0 || i + n > text.size()) return 0;
  for (size_t k = 1; k < n; ++k)
    if ((static_cast<unsigned char>(text[i + k]) & 0xC0) != 0x80) return 0;
  return n;
}

inline std::string escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7F) {
      out += char(c);
      ++i;
    } else if (const size_t n = c >= 0x80 ? utf8_length(text, i) : 0; n > 0) {
      out.append(text.substr(i, n));
      i += n;
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
      ++i;
    }
  }
  return out;
}

inline std::string cut_middle(std::string_view text, size_t keep) {
  if (text.size() <= keep) return std::string(text);
  const size_t head = keep * 2 / 3, tail = keep - head;
  return std::string(text.substr(0, head)) + "...(" +
         std::to_string(text.size() - head - tail) + " bytes left out)..." +
         std::string(text.substr(text.size() - tail));
}

}  // namespace printable_detail

// `text` with every byte that is not printable ASCII or valid UTF-8 written as \xNN (newlines and
// tabs too: the result is one line), each quoted part longer than kMaxQuotedBytes and then the
// whole cut in the middle.
inline std::string printable(std::string_view text) {
  using namespace printable_detail;
  std::string shortened;
  for (size_t i = 0; i < text.size();) {
    const size_t open = text.find('\'', i);
    const size_t close = open == std::string_view::npos ? open : text.find('\'', open + 1);
    if (close == std::string_view::npos) {
      shortened.append(text.substr(i));
      break;
    }
    shortened.append(text.substr(i, open + 1 - i));
    shortened += cut_middle(text.substr(open + 1, close - open - 1), kMaxQuotedBytes);
    shortened += '\'';
    i = close + 1;
  }
  return escape(cut_middle(shortened, kMaxMessageBytes));
}

}  // namespace rp::app
