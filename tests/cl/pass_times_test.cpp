// rp::cl::PassTimes: the per-pass times of a frame, a small inline map (src/cl/profiler.h) that
// replaced std::map<std::string, double> so that collecting a frame's times allocates nothing.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "cl/profiler.h"

namespace rp::cl {
namespace {

std::vector<std::string> names(const PassTimes& t) {
  std::vector<std::string> out;
  for (const auto& [name, ms] : t) out.push_back(name);
  return out;
}

TEST(PassTimes, KeepsNamesInOrderAndSumsLikeAMap) {
  PassTimes t;
  EXPECT_TRUE(t.empty());
  t["tone_map"] += 1.0;
  t["bloom"] += 2.0;
  t["light"] += 0.5;
  t["bloom"] += 0.25;
  t["visibility"] += 4.0;
  EXPECT_EQ(names(t), (std::vector<std::string>{"bloom", "light", "tone_map", "visibility"}));
  EXPECT_EQ(t.size(), 4u);
  EXPECT_DOUBLE_EQ(t.at("bloom"), 2.25);
  EXPECT_DOUBLE_EQ(t["light"], 0.5);
  EXPECT_EQ(t.count("light"), 1u);
  EXPECT_EQ(t.count("taa"), 0u);
  EXPECT_EQ(t.find("taa"), t.end());
  EXPECT_THROW(t.at("taa"), std::out_of_range);
  const PassTimes copy = t;
  EXPECT_EQ(copy, t);
  EXPECT_DOUBLE_EQ(copy.at("visibility"), 4.0);
  t.clear();
  EXPECT_TRUE(t.empty());
  EXPECT_EQ(t.begin(), t.end());
  t["taa"] = 3.0;  // reuses a slot that held another name
  EXPECT_EQ(names(t), std::vector<std::string>{"taa"});
  EXPECT_DOUBLE_EQ(t.at("taa"), 3.0);
}

TEST(PassTimes, HoldsLongNamesAndRefusesMoreThanItsCapacity) {
  PassTimes t;
  const std::string long_name = "a_pass_name_longer_than_the_short_string_buffer";
  t[long_name] = 1.0;
  for (size_t i = 1; i < PassTimes::kCapacity; ++i) t["pass_" + std::to_string(100 + i)] = double(i);
  EXPECT_EQ(t.size(), PassTimes::kCapacity);
  EXPECT_DOUBLE_EQ(t.at(long_name), 1.0);
  EXPECT_DOUBLE_EQ(t.at("pass_131"), 31.0);
  EXPECT_NO_THROW(t["pass_101"] += 1.0);  // an existing name needs no new slot
  EXPECT_THROW(t["one_too_many"], std::length_error);
  EXPECT_EQ(t.size(), PassTimes::kCapacity);
}

}  // namespace
}  // namespace rp::cl
