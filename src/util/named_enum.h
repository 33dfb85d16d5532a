// One name table per enum: the command line's choices, the window title, the bench's JSON and
// the tests all print and parse an enum's values through it, so a new value is one table row.
//
// An enum E takes part by declaring, in its own namespace, a table and an overload that returns
// it (found by argument-dependent lookup):
//   constexpr NamedValue<ShadowMode> kShadowModeNames[] = {{ShadowMode::kHard, "hard"}, ...};
//   constexpr std::span<const NamedValue<ShadowMode>> names(ShadowMode) { return kShadowModeNames; }
// Header-only and free of OpenCL, so the scene, the path tracer and the fuzzers can use it.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rp {

template <typename E>
struct NamedValue {
  E value;
  std::string_view name;
};

// The name of `value` ("" for a value the table lacks, which a test of each table rules out).
template <typename E>
constexpr std::string_view name_of(E value) {
  for (const NamedValue<E>& entry : names(E{}))
    if (entry.value == value) return entry.name;
  return {};
}

// The value named `name` exactly (case-sensitive, as typed on the command line); nullopt for
// any other text.
template <typename E>
constexpr std::optional<E> parse_name(std::string_view name) {
  for (const NamedValue<E>& entry : names(E{}))
    if (entry.name == name) return entry.value;
  return std::nullopt;
}

// Every name, in the table's order (the CLI's list of choices, a help text).
template <typename E>
std::vector<std::string> name_list() {
  std::vector<std::string> out;
  for (const NamedValue<E>& entry : names(E{})) out.emplace_back(entry.name);
  return out;
}

}  // namespace rp
