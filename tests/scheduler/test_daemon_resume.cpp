// SPDX-License-Identifier: GPL-3.0-or-later
// An optimisation survives SIGKILL of the daemon, in the Latin-hypercube batch and again in an
// infill batch: it ends with the same evaluations, best point and value as an uninterrupted run,
// and the cases computed are exactly those needed (none repeated, none lost).
#include <set>

#include <gtest/gtest.h>

#include "daemon_fixture.hpp"

namespace auvloop::test {
namespace {

constexpr int kInitialPoints = 8;

v1::SubmitOptimizationRequest study_request(const std::string& case_name) {
  v1::SubmitOptimizationRequest req;
  auto* src = req.mutable_source();
  src->set_source_name("study.toml");
  src->set_toml(R"(name = "resume"
[problem]
type = "case"
case = "cases/step.toml"
[[parameter]]
name = "kp"
lower = 0.2
upper = 3.5
[[parameter]]
name = "kd"
lower = 0
upper = 1
[optimizer]
initial_points = 8
max_iterations = 4
epsilon = 0
seed = 3
)");
  // Long enough (60 s at 2 ms) that the kills land while cases run.
  (*src->mutable_files())["cases/step.toml"] = heading_case(case_name, 60, 0.002);
  return req;
}

std::string submit(Daemon& d, const std::string& case_name) {
  v1::Optimization o;
  auto c = Daemon::ctx();
  const auto st = d.stub().SubmitOptimization(c.get(), study_request(case_name), &o);
  if (!st.ok()) throw std::runtime_error(st.error_message());
  return o.id();
}

void wait_executions(const Daemon& d, std::size_t n) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (d.executions().size() < n && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_GE(d.executions().size(), n);
}

TEST(DaemonResume, KilledTwiceTheOptimisationEndsAsIfUninterrupted) {
  Daemon reference({"--slots", "2", "--no-plots"});
  reference.start();
  const auto expected = reference.wait_optimization(submit(reference, "step"));
  ASSERT_EQ(expected.state(), v1::SUCCEEDED) << expected.failure();
  ASSERT_GT(expected.evaluations_done(), kInitialPoints);

  Daemon d({"--slots", "2", "--no-plots"});
  d.start();
  const std::string id = submit(d, "step");
  wait_executions(d, 3);  // in the Latin hypercube batch
  d.kill9();
  const std::size_t after_first_kill = d.executions().size();
  EXPECT_LT(after_first_kill, static_cast<std::size_t>(kInitialPoints));
  d.start();
  wait_executions(d, kInitialPoints + 1);  // in the first infill batch
  d.kill9();
  const std::size_t after_second_kill = d.executions().size();
  EXPECT_LT(after_second_kill, static_cast<std::size_t>(expected.evaluations_done()));
  d.start();
  const auto got = d.wait_optimization(id);
  ASSERT_EQ(got.state(), v1::SUCCEEDED) << got.failure();

  EXPECT_EQ(got.best_value(), expected.best_value());  // bit for bit
  EXPECT_EQ(got.best_parameters().at("kp"), expected.best_parameters().at("kp"));
  EXPECT_EQ(got.best_parameters().at("kd"), expected.best_parameters().at("kd"));
  ASSERT_EQ(got.evaluations_size(), expected.evaluations_size());
  for (int i = 0; i < got.evaluations_size(); ++i) {
    EXPECT_EQ(got.evaluations(i).batch(), expected.evaluations(i).batch());
    EXPECT_EQ(got.evaluations(i).point(), expected.evaluations(i).point());
    EXPECT_EQ(got.evaluations(i).value(), expected.evaluations(i).value()) << i;
  }
  // Every evaluation computed exactly once across the three daemon lives.
  const auto runs = d.executions();
  EXPECT_EQ(runs.size(), static_cast<std::size_t>(got.evaluations_done()));
  EXPECT_EQ(std::set<std::string>(runs.begin(), runs.end()).size(), runs.size());
  // A job queued again after a kill that finds its own stored result is no cache hit: every
  // point here is distinct, so no job may claim one.
  v1::ListJobsRequest req;
  req.set_optimization_id(id);
  req.set_limit(1000);
  v1::ListJobsResponse jobs;
  auto c = Daemon::ctx();
  ASSERT_TRUE(d.stub().ListJobs(c.get(), req, &jobs).ok());
  for (const auto& j : jobs.jobs()) EXPECT_FALSE(j.cache_hit()) << j.id() << " " << j.name();
}

TEST(DaemonResume, CrashingEvaluationsAreFailedEvaluationsAndCancelledRunsResume) {
  Daemon d({"--slots", "2", "--no-plots"}, {{"AUVLOOP_WORKER_FAILPOINT", "abort:crashing"}});
  d.start();
  // Every evaluation of this study aborts: the optimizer records failures and stops.
  const auto crashed = d.wait_optimization(submit(d, "crashing"));
  EXPECT_EQ(crashed.state(), v1::FAILED);
  EXPECT_EQ(crashed.evaluations_failed(), crashed.evaluations_done());
  EXPECT_GE(crashed.evaluations_done(), kInitialPoints);
  EXPECT_TRUE(d.alive());

  // Cancel a healthy one in its first batch, then resume it: it completes.
  const std::string id = submit(d, "step");
  wait_executions(d, 2);
  v1::IdRequest req;
  req.set_id(id);
  v1::CancelResponse cancelled;
  auto c1 = Daemon::ctx();
  ASSERT_TRUE(d.stub().Cancel(c1.get(), req, &cancelled).ok());
  EXPECT_EQ(d.wait_optimization(id).state(), v1::CANCELLED);
  v1::Optimization resumed;
  auto c2 = Daemon::ctx();
  ASSERT_TRUE(d.stub().Resume(c2.get(), req, &resumed).ok());
  const auto done = d.wait_optimization(id);
  EXPECT_EQ(done.state(), v1::SUCCEEDED);
  // Points that were running when it was cancelled are computed again, not counted as failed.
  EXPECT_EQ(done.evaluations_failed(), 0);
  const auto runs = d.executions();
  EXPECT_EQ(std::set<std::string>(runs.begin(), runs.end()).size(), runs.size());
}

}  // namespace
}  // namespace auvloop::test
