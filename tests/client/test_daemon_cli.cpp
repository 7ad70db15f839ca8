// SPDX-License-Identifier: GPL-3.0-or-later
// The daemon commands of `auvloop` as a user types them, against a daemon the CLI starts itself
// on a temporary socket and state directory (chosen through the environment variables).
#include <cstdlib>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "temp_dir.hpp"

namespace auvloop::test {
namespace {
using ::testing::HasSubstr;

class DaemonCli : public ::testing::Test {
 protected:
  void SetUp() override {
    setenv("AUVLOOP_SOCKET", (dir_.path() / "d.sock").c_str(), 1);
    setenv("AUVLOOP_STATE_DIR", (dir_.path() / "state").c_str(), 1);
    setenv("AUVLOOP_DAEMON", AUVLOOPD, 1);
  }
  void TearDown() override { run_cli("daemon stop"); }
  static std::string example(const std::string& name) {
    return std::string(AUVLOOP_SOURCE_DIR) + "/examples/" + name;
  }
  TempDir dir_;
};

TEST_F(DaemonCli, WithoutADaemonTheErrorSaysHowToStartOne) {
  const auto r = run_cli("jobs");
  EXPECT_EQ(r.exit_code, 5);
  EXPECT_THAT(r.output, HasSubstr("auvloop daemon start"));
}

TEST_F(DaemonCli, SubmitWaitCacheJobsResultsAndStop) {
  ASSERT_EQ(run_cli("daemon start --slots 2").exit_code, 0);
  EXPECT_THAT(run_cli("daemon start").output, HasSubstr("running already"));

  auto r = run_cli("submit " + example("heading-step.toml") + " --wait");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("j1 heading-step: succeeded"));
  r = run_cli("submit " + example("heading-step.toml"));
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("from the cache, nothing was run"));

  r = run_cli("jobs --all --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto jobs = nlohmann::json::parse(r.output);
  ASSERT_EQ(jobs["jobs"].size(), 2U);
  EXPECT_EQ(jobs["jobs"][0]["key"], jobs["jobs"][1]["key"]);

  r = run_cli("results show j1");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("itae_deg_s2"));
  const auto plots = dir_.path() / "plots";
  r = run_cli("results plot j1 --out " + plots.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(plots / "heading.png")) << r.output;
  r = run_cli("results export j1 --out " + (dir_.path() / "run").string());
  EXPECT_TRUE(std::filesystem::exists(dir_.path() / "run" / "manifest.json")) << r.output;

  // Mistakes: a case file with an error is refused with file:line; unknown ids are errors.
  const auto bad = dir_.write("bad.toml", "name = \"bad\"\n[time]\ndt = -1\nduration = 1\n");
  r = run_cli("submit " + bad.string());
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(r.output, HasSubstr("bad.toml:3"));
  EXPECT_EQ(run_cli("status j999").exit_code, 4);
  EXPECT_EQ(run_cli("status ../j1").exit_code, 3);

  EXPECT_EQ(run_cli("daemon stop").exit_code, 0);
  EXPECT_EQ(run_cli("jobs").exit_code, 5);
}

TEST_F(DaemonCli, OptimiseOnTheDaemonThenResumeSaysItIsFinished) {
  auto r = run_cli("optimize " + example("branin-optimization.toml") + " --daemon --wait --start");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("o1 branin: succeeded"));
  r = run_cli("status o1 --json");
  ASSERT_EQ(r.exit_code, 0);
  const auto o = nlohmann::json::parse(r.output);
  EXPECT_TRUE(o["has_best"].get<bool>());
  // Branin's global minimum is 0.397887 (Dixon and Szego); the run gets within a few percent.
  EXPECT_NEAR(o["best_value"].get<double>(), 0.397887, 0.05);
  r = run_cli("resume o1");
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_THAT(r.output, HasSubstr("nothing to resume"));
}

}  // namespace
}  // namespace auvloop::test
