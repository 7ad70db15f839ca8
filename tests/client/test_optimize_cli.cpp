// SPDX-License-Identifier: GPL-3.0-or-later
// `auvloop optimize`: the paper's setup lowers ITAE and writes its results; test functions run;
// bad optimisation files fail with file:line and the reason.
#include <array>
#include <cstdio>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "temp_dir.hpp"

using ::testing::HasSubstr;

namespace {
using auvloop::test::run_cli;
const auto& run = run_cli;
const std::string kExamples = std::string(AUVLOOP_SOURCE_DIR) + "/examples/";
const std::string kTemplate = R"(name = "t"
[problem]
type = "case"
case = ")" + kExamples + R"(heading-step.toml"
[[parameter]]
name = "kp"
lower = LOWER
upper = UPPER
[objective]
index = "INDEX"
[optimizer]
initial_points = 6
max_iterations = 1
)";
std::string study(const std::string& lower, const std::string& upper, const std::string& index) {
  std::string s = kTemplate;
  s.replace(s.find("LOWER"), 5, lower);
  s.replace(s.find("UPPER"), 5, upper);
  s.replace(s.find("INDEX"), 5, index);
  return s;
}
}  // namespace

TEST(OptimizeCli, PaperSetupLowersItaeAndWritesResults) {
  auvloop::test::TempDir tmp;
  const auto r =
      run("optimize " + kExamples + "pid-optimization.toml --out " + tmp.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("ITAE (deg s^2)"));
  std::ifstream in(tmp.path() / "optimization.json");
  const auto j = nlohmann::json::parse(in);
  const double best = j["best"]["value"];
  std::ifstream before(tmp.path() / "before" / "metrics.json");
  EXPECT_LT(best, nlohmann::json::parse(before)["itae_deg_s2"].get<double>());
  EXPECT_FALSE(j["stop_reason"].get<std::string>().empty());
  EXPECT_EQ(j["study"]["evaluations"].size(), j["evaluations"].size());
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "convergence.png"));
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "before-after" / "heading.png"));
}

TEST(OptimizeCli, TestFunctionsRun) {
  auvloop::test::TempDir tmp;
  const auto r =
      run("optimize " + kExamples + "branin-optimization.toml --out " + tmp.path().string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("best: f = 0.39"));
}

TEST(OptimizeCli, BadFilesNameLineAndReason) {
  auvloop::test::TempDir tmp;
  auto check = [&](const std::string& text, const std::string& expected) {
    const auto path = tmp.write("opt.toml", text);
    const auto r = run("optimize " + path.string() + " --out " + (tmp.path() / "o").string());
    EXPECT_EQ(r.exit_code, 3) << r.output;
    EXPECT_THAT(r.output, HasSubstr(expected));
  };
  check(
      study("2", "1", "itae"),
      "opt.toml:8:1: parameter[0].upper: must exceed lower = 2 (bounds reversed or of zero width)");
  check(study("1", "1", "itae"), "bounds reversed or of zero width");
  check(study("0", "1", "speed"), "opt.toml:10:1: objective.index: \"speed\" is not allowed");
}

TEST(OptimizeCli, WeightedObjectiveAndConstraints) {
  auvloop::test::TempDir tmp;
  std::string text = study("0", "3.5", "weighted");
  text += "[objective.weights]\nitae = 1.0\novershoot = 20.0\n[constraints]\nmax_overshoot = 80\n";
  const auto path = tmp.write("w.toml", text);
  const auto r = run("optimize " + path.string() + " --out " + (tmp.path() / "o").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream in(tmp.path() / "o" / "optimization.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_GT(j["failures"].get<int>(), 0);  // the constraint was active ...
  EXPECT_FALSE(j["best"].is_null());       // ... but not everywhere
  // Every evaluation's objective is ITAE + 20 x overshoot, and any overshoot above 80 % failed.
  for (const auto& e : j["study"]["evaluations"]) {
    const auto& m = e["indices"];
    if (e["objective"].is_null()) {
      EXPECT_NE(e["failure"].get<std::string>().find("overshoot"), std::string::npos);
      EXPECT_GT(m["overshoot_percent"].get<double>(), 80.0);
    } else {
      EXPECT_NEAR(e["objective"].get<double>(),
                  m["itae_deg_s2"].get<double>() + 20 * m["overshoot_percent"].get<double>(), 1e-6);
      EXPECT_LE(m["overshoot_percent"].get<double>(), 80.0);
    }
  }
}
