// SPDX-License-Identifier: GPL-3.0-or-later
// auvloopd end to end: a real daemon on a temporary socket and state directory, driven over gRPC.
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <set>

#include <grpcpp/generic/generic_stub.h>
#include <gtest/gtest.h>

#include "daemon_fixture.hpp"

namespace auvloop::test {
namespace {
namespace fs = std::filesystem;

// A status for an arbitrary byte string sent as the request of `method`.
grpc::Status raw_call(const fs::path& socket, const std::string& method, const std::string& bytes) {
  auto channel = grpc::CreateChannel("unix:" + socket.string(), grpc::InsecureChannelCredentials());
  grpc::GenericStub stub(channel);
  grpc::CompletionQueue cq;
  grpc::Slice slice(bytes);
  grpc::ByteBuffer request(&slice, 1), response;
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
  auto call = stub.PrepareUnaryCall(&ctx, method, request, &cq);
  call->StartCall();
  grpc::Status status;
  call->Finish(&response, &status, reinterpret_cast<void*>(1));
  void* tag = nullptr;
  bool ok = false;
  cq.Next(&tag, &ok);
  cq.Shutdown();
  while (cq.Next(&tag, &ok)) {
  }
  return status;
}

TEST(Daemon, SubmitWatchResultThenResubmitIsACacheHit) {
  Daemon d({"--slots", "2"});
  d.start();
  const auto job = d.submit(heading_case("step"));
  EXPECT_EQ(job.id(), "j1");
  EXPECT_FALSE(job.cache_hit());

  // Watch streams snapshots until the job ends.
  v1::IdRequest req;
  req.set_id(job.id());
  auto ctx = Daemon::ctx();
  auto reader = d.stub().Watch(ctx.get(), req);
  v1::WatchEvent ev;
  v1::State last = v1::STATE_UNSPECIFIED;
  int events = 0;
  while (reader->Read(&ev)) {
    ASSERT_TRUE(ev.has_job());
    last = ev.job().state();
    ++events;
  }
  ASSERT_TRUE(reader->Finish().ok());
  EXPECT_EQ(last, v1::SUCCEEDED);
  EXPECT_GE(events, 1);

  v1::Result result;
  auto c2 = Daemon::ctx();
  ASSERT_TRUE(d.stub().GetResult(c2.get(), req, &result).ok());
  EXPECT_EQ(result.key(), job.key());
  EXPECT_EQ(result.status(), "completed");
  EXPECT_NE(result.metrics_json().find("itae_deg_s2"), std::string::npos);

  v1::IdRequest by_prefix;  // a unique prefix of the key names the result too
  by_prefix.set_id(job.key().substr(0, 8));
  v1::Result same;
  auto c4 = Daemon::ctx();
  ASSERT_TRUE(d.stub().GetResult(c4.get(), by_prefix, &same).ok());
  EXPECT_EQ(same.key(), job.key());

  const auto again = d.submit(heading_case("step"));
  EXPECT_EQ(again.state(), v1::SUCCEEDED);  // at once, in the reply
  EXPECT_TRUE(again.cache_hit());
  EXPECT_EQ(again.key(), job.key());
  EXPECT_EQ(d.executions().size(), 1U);  // nothing was run the second time

  // The exported files are the cached run directory.
  auto c3 = Daemon::ctx();
  auto files = d.stub().ExportResult(c3.get(), req);
  v1::FileChunk chunk;
  std::set<std::string> names;
  while (files->Read(&chunk)) names.insert(chunk.path());
  ASSERT_TRUE(files->Finish().ok());
  EXPECT_TRUE(names.contains("manifest.json"));
  EXPECT_TRUE(names.contains("timeseries.csv"));
}

TEST(Daemon, IdenticalCasesInFlightRunOnce) {
  Daemon d({"--slots", "2", "--no-plots"});
  d.start();
  const std::string toml = heading_case("twin", 300, 0.002);  // long enough to overlap
  const auto a = d.submit(toml);
  const auto b = d.submit(toml);
  EXPECT_EQ(a.key(), b.key());
  EXPECT_EQ(d.wait_job(a.id()).state(), v1::SUCCEEDED);
  const auto bb = d.wait_job(b.id());
  EXPECT_EQ(bb.state(), v1::SUCCEEDED);
  EXPECT_TRUE(bb.cache_hit());
  EXPECT_EQ(d.executions().size(), 1U);
}

TEST(Daemon, CrashHangAndDivergenceFailWithReasonsAndTheDaemonCarriesOn) {
  Daemon d({"--slots", "2", "--no-plots"},
           {{"AUVLOOP_WORKER_FAILPOINT", "abort:crasher,hang:hanger"}});
  d.start();
  const auto crash = d.submit(heading_case("crasher"));
  const auto hang = d.submit(heading_case("hanger"), 1.0);  // 1 s wall-time limit
  // The linearised plant is unstable about straight running (docs/derivative-plant.md).
  const auto diverge = d.submit(heading_case("diverger", 30, 0.01, 90, "linearized"));
  const auto good = d.submit(heading_case("good"));

  const auto c = d.wait_job(crash.id());
  EXPECT_EQ(c.state(), v1::FAILED);
  EXPECT_NE(c.failure().find("SIGABRT"), std::string::npos) << c.failure();
  EXPECT_NE(c.failure().find("worker.log"), std::string::npos) << c.failure();
  const auto h = d.wait_job(hang.id());
  EXPECT_EQ(h.state(), v1::FAILED);
  EXPECT_NE(h.failure().find("timed out"), std::string::npos) << h.failure();
  const auto v = d.wait_job(diverge.id());
  EXPECT_EQ(v.state(), v1::FAILED);
  EXPECT_FALSE(v.failure().empty());
  EXPECT_EQ(d.wait_job(good.id()).state(), v1::SUCCEEDED);
  EXPECT_TRUE(d.alive());

  // A divergence is a result (deterministic): cached, so asking again runs nothing.
  const auto again = d.submit(heading_case("diverger", 30, 0.01, 90, "linearized"));
  EXPECT_EQ(again.state(), v1::FAILED);
  EXPECT_TRUE(again.cache_hit());
}

TEST(Daemon, CancelStopsARunningJob) {
  Daemon d({"--no-plots"}, {{"AUVLOOP_WORKER_FAILPOINT", "hang:sleeper"}});
  d.start();
  const auto job = d.submit(heading_case("sleeper"));
  ASSERT_EQ(d.wait_running(job.id()), v1::RUNNING);
  EXPECT_EQ(d.cancel(job.id()), 1);
  EXPECT_EQ(d.wait_job(job.id(), 30).state(), v1::CANCELLED);
}

// The cancel is on disk before the reply: a daemon killed right after it does not run the job
// again when it restarts.
TEST(Daemon, CancelSurvivesAKillRightAfterTheReply) {
  Daemon d({"--no-plots"}, {{"AUVLOOP_WORKER_FAILPOINT", "hang:sleeper"}});
  d.start();
  const auto job = d.submit(heading_case("sleeper"));
  ASSERT_EQ(d.wait_running(job.id()), v1::RUNNING);
  ASSERT_EQ(d.cancel(job.id()), 1);
  d.kill9();
  d.start();
  std::this_thread::sleep_for(std::chrono::milliseconds(600));  // a dispatch round or more
  EXPECT_EQ(d.job(job.id()).state(), v1::CANCELLED);
  v1::DaemonStatus status;
  auto sc = Daemon::ctx();
  ASSERT_TRUE(d.stub().Status(sc.get(), v1::StatusRequest(), &status).ok());
  EXPECT_EQ(status.running(), 0);
  EXPECT_EQ(status.queued(), 0);
}

// A worker stopped after storing its result and before logging its execution: the case was
// computed, so it has its one line in executions.log, and the job ends with the stored result
// (timed out) or stays cancelled (cancelled); a resubmission is a cache hit that adds no line.
TEST(Daemon, AWorkerStoppedAfterStoringItsResultIsLoggedOnce) {
  Daemon d({"--slots", "2", "--no-plots"},
           {{"AUVLOOP_WORKER_FAILPOINT", "hang-stored:late,hang-stored:cut"}});
  d.start();
  const auto late = d.submit(heading_case("late"), 3.0);  // 3 s wall-time limit
  const auto cut = d.submit(heading_case("cut"));
  const auto stored = [&](const std::string& key) {
    return std::filesystem::exists(d.state_dir() / "cache" / key.substr(0, 2) / key);
  };
  for (int i = 0; i < 3000 && !stored(cut.key()); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(stored(cut.key()));
  EXPECT_EQ(d.job(cut.id()).state(), v1::RUNNING);  // hung before logging
  EXPECT_EQ(d.cancel(cut.id()), 1);
  EXPECT_EQ(d.wait_job(cut.id(), 30).state(), v1::CANCELLED);

  const auto l = d.wait_job(late.id(), 60);
  EXPECT_EQ(l.state(), v1::SUCCEEDED) << l.failure();
  EXPECT_FALSE(l.cache_hit());
  const auto runs = d.executions();
  EXPECT_EQ(runs.size(), 2U);
  EXPECT_EQ(std::set<std::string>(runs.begin(), runs.end()),
            (std::set<std::string>{late.key(), cut.key()}));

  const auto again = d.submit(heading_case("cut"));
  EXPECT_EQ(again.state(), v1::SUCCEEDED);
  EXPECT_TRUE(again.cache_hit());
  EXPECT_EQ(d.executions().size(), 2U);
}

TEST(Daemon, DrainingStopRecordsTheRunningJobAndExits) {
  Daemon d({"--no-plots"}, {{"AUVLOOP_WORKER_FAILPOINT", "hang:slow"}});
  d.start();
  const auto job = d.submit(heading_case("slow"), 1.0);  // ends by its 1 s timeout
  d.wait_running(job.id());
  v1::ShutdownRequest req;
  req.set_drain(true);
  v1::ShutdownResponse resp;
  auto c = Daemon::ctx();
  d.stub().Shutdown(c.get(), req, &resp);  // (the reply may be cut short by the exit)
  ASSERT_TRUE(d.wait_exit(30)) << "a draining stop must end once its jobs have ended";
  d.start();
  const auto after = d.job(job.id());
  EXPECT_EQ(after.state(), v1::FAILED);  // recorded during the drain, not queued again
  EXPECT_NE(after.failure().find("timed out"), std::string::npos) << after.failure();
}

TEST(Daemon, CorruptCacheEntryIsDetectedAndRecomputed) {
  Daemon d({"--no-plots"});
  d.start();
  const auto first = d.wait_job(d.submit(heading_case("fragile")).id());
  ASSERT_EQ(first.state(), v1::SUCCEEDED);
  std::ofstream(fs::path(first.result_path()) / "timeseries.csv") << "tampered\n";
  const auto second = d.submit(heading_case("fragile"));
  EXPECT_FALSE(second.cache_hit());
  EXPECT_EQ(d.wait_job(second.id()).state(), v1::SUCCEEDED);
  EXPECT_EQ(d.executions().size(), 2U);
}

TEST(Daemon, HostileRequestsGetErrorsAndNeverCrashIt) {
  Daemon d({"--no-plots"});
  d.start();
  auto code = [&](auto&& call) {
    auto c = Daemon::ctx();
    return call(c.get()).error_code();
  };
  v1::Job job;
  v1::Result result;
  const std::vector<std::string> bad_ids{"../../etc/passwd",
                                         "j1/../../x",
                                         "j",
                                         "j-1",
                                         "j0",
                                         "o1",
                                         std::string(100000, 'j'),
                                         "j99999999999999999999999",
                                         ""};
  for (const auto& id : bad_ids) {
    v1::IdRequest req;
    req.set_id(id);
    EXPECT_EQ(code([&](auto* c) { return d.stub().GetJob(c, req, &job); }),
              grpc::StatusCode::INVALID_ARGUMENT)
        << id.substr(0, 40);
    EXPECT_EQ(code([&](auto* c) { return d.stub().GetResult(c, req, &result); }),
              grpc::StatusCode::INVALID_ARGUMENT)
        << id.substr(0, 40);
  }
  v1::IdRequest missing;
  missing.set_id("j12345");
  EXPECT_EQ(code([&](auto* c) { return d.stub().GetJob(c, missing, &job); }),
            grpc::StatusCode::NOT_FOUND);
  missing.set_id(std::string(64, 'a'));
  EXPECT_EQ(code([&](auto* c) { return d.stub().GetResult(c, missing, &result); }),
            grpc::StatusCode::NOT_FOUND);

  auto submit = [&](const std::string& toml, std::map<std::string, std::string> files = {}) {
    v1::SubmitCaseRequest req;
    req.mutable_source()->set_source_name("hostile.toml");
    req.mutable_source()->set_toml(toml);
    for (const auto& [k, v] : files) (*req.mutable_source()->mutable_files())[k] = v;
    v1::Job j;
    auto c = Daemon::ctx();
    return d.stub().SubmitCase(c.get(), req, &j);
  };
  EXPECT_EQ(submit("\x01[[[=\"\x7f").error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(submit(std::string(2 << 20, 'x')).error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(submit("name = 7\n[time]\ndt = \"fast\"\n").error_code(),
            grpc::StatusCode::INVALID_ARGUMENT);
  // Paths in a case name files of the request, never the daemon's disk.
  for (const std::string& vehicle :
       {std::string("/etc/passwd"), std::string("../../../etc/passwd")}) {
    std::string toml = heading_case("nosy");
    toml.insert(0, "vehicle = \"" + vehicle + "\"\n");
    const auto st = submit(toml);
    EXPECT_EQ(st.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(st.error_message().find("not sent with the request"), std::string::npos)
        << st.error_message();
  }
  const auto status_message = submit("name = \"x\"\nbogus_key = 1\n").error_message();
  EXPECT_NE(status_message.find("hostile.toml:"), std::string::npos) << status_message;

  // Bytes that are not the request message, and unknown fields.
  const std::string method = "/auvloop.v1.Scheduler/SubmitCase";
  EXPECT_FALSE(raw_call(d.socket(), method, std::string("\x0a\xff\xff\xff\xff\x0f", 6)).ok());
  EXPECT_FALSE(raw_call(d.socket(), method, std::string("\x08\x01", 2)).ok());
  // A CaseSource whose toml (a proto3 string) is not UTF-8.
  EXPECT_FALSE(raw_call(d.socket(), method, std::string("\x0a\x04\x12\x02\xff\xfe", 6)).ok());
  EXPECT_EQ(raw_call(d.socket(), method, std::string("\xf8\x3f\x01", 3)).error_code(),
            grpc::StatusCode::INVALID_ARGUMENT);  // unknown field ignored; the case is empty
  EXPECT_FALSE(raw_call(d.socket(), "/auvloop.v1.Scheduler/NoSuchMethod", "").ok());
  EXPECT_FALSE(raw_call(d.socket(), method, std::string(40 << 20, 'x')).ok());  // > max size

  // An optimisation that could ask for more evaluations than any daemon should run.
  v1::SubmitOptimizationRequest big;
  big.mutable_source()->set_source_name("big.toml");
  big.mutable_source()->set_toml(R"(name = "big"
[problem]
type = "test-function"
function = "branin"
[optimizer]
initial_points = 10000
max_iterations = 10000
)");
  v1::Optimization o;
  auto oc = Daemon::ctx();
  const auto big_status = d.stub().SubmitOptimization(oc.get(), big, &o);
  EXPECT_EQ(big_status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(big_status.error_message().find("evaluations"), std::string::npos)
      << big_status.error_message();

  EXPECT_TRUE(d.alive());
  v1::DaemonStatus s;
  auto c = Daemon::ctx();
  EXPECT_TRUE(d.stub().Status(c.get(), v1::StatusRequest(), &s).ok());
  EXPECT_EQ(s.jobs_total(), 0);
}

TEST(Daemon, SocketAndStateAreOwnerOnlyAndTcpNeedsTheToken) {
  Daemon d({"--tcp", "0"});
  d.start();
  struct stat st {};
  ASSERT_EQ(stat(d.socket().c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 077, 0U) << std::oct << st.st_mode;
  ASSERT_EQ(stat(d.state_dir().c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 077, 0U);
  ASSERT_EQ(stat((d.state_dir() / "token").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 077, 0U);

  std::string port, token;
  std::ifstream(d.state_dir() / "tcp-port") >> port;
  std::ifstream(d.state_dir() / "token") >> token;
  ASSERT_FALSE(port.empty());
  ASSERT_EQ(token.size(), 64U);
  auto stub = v1::Scheduler::NewStub(
      grpc::CreateChannel("127.0.0.1:" + port, grpc::InsecureChannelCredentials()));
  auto status_with = [&](const std::string& auth) {
    auto c = Daemon::ctx(10);
    if (!auth.empty()) c->AddMetadata("authorization", auth);
    v1::DaemonStatus s;
    return stub->Status(c.get(), v1::StatusRequest(), &s).error_code();
  };
  EXPECT_EQ(status_with(""), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(status_with("Bearer " + std::string(64, '0')), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(status_with(token), grpc::StatusCode::UNAUTHENTICATED);  // the scheme is required
  EXPECT_EQ(status_with("Bearer " + token), grpc::StatusCode::OK);
}

TEST(Daemon, RefusesASecondDaemonOnTheSameStateOrSocketAndStopsCleanly) {
  Daemon d;
  d.start();
  const std::string cmd = std::string(AUVLOOPD) + " --state-dir " + d.state_dir().string() +
                          " --socket " + (d.dir() / "other.sock").string() + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out(512, '\0');
  out.resize(fread(out.data(), 1, out.size(), p));
  EXPECT_EQ(WEXITSTATUS(pclose(p)), 4);
  EXPECT_NE(out.find("another auvloopd"), std::string::npos) << out;
  const int status = d.stop();
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_FALSE(fs::exists(d.socket()));
}

}  // namespace
}  // namespace auvloop::test
