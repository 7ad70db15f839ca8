// SPDX-License-Identifier: GPL-3.0-or-later
// Eight clients submit 100 distinct cases each at the same time: all 800 are recorded, run once
// and finish; none is lost or duplicated.
#include <set>

#include <gtest/gtest.h>

#include "daemon_fixture.hpp"

namespace auvloop::test {
namespace {

TEST(DaemonLoad, EightClientsTimesOneHundredJobs) {
  Daemon d({"--slots", "2", "--no-plots"});
  d.start();
  constexpr int kClients = 8, kJobs = 100;
  std::vector<std::vector<std::string>> ids(kClients);
  std::vector<std::thread> clients;
  for (int c = 0; c < kClients; ++c) {
    clients.emplace_back([&, c] {
      // Each client its own connection, as separate processes would have.
      auto stub = v1::Scheduler::NewStub(
          grpc::CreateChannel("unix:" + d.socket().string(), grpc::InsecureChannelCredentials()));
      for (int i = 0; i < kJobs; ++i) {
        v1::SubmitCaseRequest req;
        req.mutable_source()->set_source_name("load.toml");
        // Distinct durations make distinct content keys.
        req.mutable_source()->set_toml(heading_case("load", 1.0 + 0.01 * (c * kJobs + i)));
        v1::Job job;
        auto ctx = Daemon::ctx();
        if (stub->SubmitCase(ctx.get(), req, &job).ok())
          ids[static_cast<std::size_t>(c)].push_back(job.id());
      }
    });
  }
  for (auto& t : clients) t.join();
  std::set<std::string> all;
  for (const auto& v : ids) {
    EXPECT_EQ(v.size(), static_cast<std::size_t>(kJobs));
    all.insert(v.begin(), v.end());
  }
  ASSERT_EQ(all.size(), static_cast<std::size_t>(kClients * kJobs));  // no id given twice
  for (const auto& id : all) EXPECT_EQ(d.wait_job(id, 600).state(), v1::SUCCEEDED) << id;

  v1::ListJobsRequest req;
  req.set_limit(100000);
  v1::ListJobsResponse resp;
  auto ctx = Daemon::ctx();
  ASSERT_TRUE(d.stub().ListJobs(ctx.get(), req, &resp).ok());
  EXPECT_EQ(resp.jobs_size(), kClients * kJobs);
  const auto runs = d.executions();
  EXPECT_EQ(runs.size(), static_cast<std::size_t>(kClients * kJobs));
  EXPECT_EQ(std::set<std::string>(runs.begin(), runs.end()).size(), runs.size());
}

}  // namespace
}  // namespace auvloop::test
