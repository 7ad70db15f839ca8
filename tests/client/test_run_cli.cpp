// SPDX-License-Identifier: GPL-3.0-or-later
// `auvloop run` and `auvloop compare` as a user runs them.
#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "temp_dir.hpp"

using ::testing::HasSubstr;

namespace {
using auvloop::test::run_cli;
const auto& run = run_cli;
nlohmann::json read_json(const std::filesystem::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}
const std::string kExamples = std::string(AUVLOOP_SOURCE_DIR) + "/examples/";
}  // namespace

TEST(RunCli, HeadingStepWritesAllResults) {
  auvloop::test::TempDir tmp;
  const auto out = tmp.path() / "hs";
  const auto r = run("run " + kExamples + "heading-step.toml --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("itae_deg_s2"));
  const auto metrics = read_json(out / "metrics.json");
  for (const char* k : {"rise_time_s", "settling_time_s", "peak_deg", "overshoot_percent",
                        "itae_deg_s2", "iae_deg_s", "ise_deg2_s"}) {
    EXPECT_TRUE(metrics.contains(k)) << k;
  }
  EXPECT_EQ(read_json(out / "manifest.json")["case"]["manoeuvre"]["controller"]["kp"], 1.5);
  EXPECT_TRUE(std::filesystem::exists(out / "heading.png"));
  EXPECT_TRUE(std::filesystem::exists(out / "trajectory.svg"));
}

TEST(RunCli, DivergenceExitsFourAndKeepsTheSeries) {
  auvloop::test::TempDir tmp;
  const auto out = tmp.path() / "lin";
  const auto r =
      run("run " + kExamples + "heading-step.toml --plant linearized --out " + out.string());
  EXPECT_EQ(r.exit_code, 4) << r.output;
  EXPECT_THAT(r.output, HasSubstr("diverged"));
  EXPECT_EQ(read_json(out / "manifest.json")["status"], "diverged");
  EXPECT_TRUE(std::filesystem::exists(out / "timeseries.csv"));
}

TEST(RunCli, BadCaseExitsThreeWithLine) {
  auvloop::test::TempDir tmp;
  const auto path =
      tmp.write("bad.toml",
                "name = \"x\"\n[time]\ndt = -1\nduration = 10\n[manoeuvre]\ntype = "
                "\"heading-step\"\ntarget_heading = 10\n[controller]\nkp = 1\nki = 0\nkd = 0\n");
  const auto r = run("run " + path.string());
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(r.output, HasSubstr("bad.toml:3:1: time.dt: value -1 is out of range"));
}

TEST(RunCli, CompareOverlaysRuns) {
  auvloop::test::TempDir tmp;
  ASSERT_EQ(run("run -q " + kExamples + "zigzag-10-10.toml --out " + (tmp.path() / "a").string())
                .exit_code,
            0);
  ASSERT_EQ(run("run -q " + kExamples + "zigzag-20-20.toml --out " + (tmp.path() / "b").string())
                .exit_code,
            0);
  const auto r = run("compare " + (tmp.path() / "a").string() + " " + (tmp.path() / "b").string() +
                     " --label 10/10 --label 20/20 --out " + (tmp.path() / "cmp").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("first_overshoot_deg"));
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "cmp" / "heading.png"));
  EXPECT_EQ(read_json(tmp.path() / "cmp" / "comparison.json").size(), 2U);
}

// --resume: without a checkpoint the run starts afresh and leaves none behind; a damaged one is
// refused naming it (the loop's bitwise resume is tests/engine/test_loop_checkpoint.cpp).
TEST(RunCli, ResumeStartsAfreshWithoutACheckpointAndRefusesADamagedOne) {
  auvloop::test::TempDir tmp;
  const auto out = tmp.path() / "hs";
  const auto fresh = run("run " + kExamples +
                         "heading-step.toml --resume --checkpoint-every 5 --out " + out.string());
  ASSERT_EQ(fresh.exit_code, 0) << fresh.output;
  EXPECT_TRUE(std::filesystem::exists(out / "metrics.json"));
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "hs.checkpoint"));
  const auto damaged = tmp.write("hs.checkpoint", "not a checkpoint");
  const auto r = run("run " + kExamples + "heading-step.toml --resume --out " + out.string());
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr(damaged.string()));
  EXPECT_THAT(r.output, HasSubstr("closed-loop checkpoint"));
  EXPECT_TRUE(std::filesystem::exists(damaged)) << "a refused checkpoint is kept";
}
