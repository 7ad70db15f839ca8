// SPDX-License-Identifier: GPL-3.0-or-later
#include "service.hpp"

#include <algorithm>
#include <fstream>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace auvloop::scheduler {
namespace fs = std::filesystem;
using Kind = RequestError::Kind;

namespace {
grpc::StatusCode code_of(Kind k) {
  switch (k) {
    case Kind::invalid_argument:
      return grpc::StatusCode::INVALID_ARGUMENT;
    case Kind::not_found:
      return grpc::StatusCode::NOT_FOUND;
    case Kind::failed_precondition:
      return grpc::StatusCode::FAILED_PRECONDITION;
    case Kind::resource_exhausted:
      return grpc::StatusCode::RESOURCE_EXHAUSTED;
    case Kind::unavailable:
      return grpc::StatusCode::UNAVAILABLE;
  }
  return grpc::StatusCode::UNKNOWN;
}

bool is_hex(const std::string& s) {
  return std::all_of(s.begin(), s.end(),
                     [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}
bool is_key(const std::string& s) {
  return s.size() == 64 && is_hex(s);
}
bool is_key_prefix(const std::string& s) {
  return s.size() >= 6 && s.size() < 64 && is_hex(s);
}

bool same(const std::string& a, const std::string& b) {  // constant time in the content
  if (a.size() != b.size()) return false;
  unsigned char d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d |= static_cast<unsigned char>(a[i] ^ b[i]);
  return d == 0;
}

int limit_of(int requested) {
  return requested > 0 ? std::min(requested, 100000) : 200;
}

bool terminal(v1::State s) {
  return s == v1::SUCCEEDED || s == v1::FAILED || s == v1::CANCELLED;
}
}  // namespace

SchedulerService::SchedulerService(Scheduler& scheduler, std::string token,
                                   std::function<void(bool)> shutdown)
    : scheduler_(scheduler), token_(std::move(token)), shutdown_(std::move(shutdown)) {}

grpc::Status SchedulerService::guarded(grpc::ServerContext* ctx,
                                       const std::function<void()>& body) {
  if (!ctx->peer().starts_with("unix:")) {
    // Any other peer came through the loopback TCP listener: it must present the token.
    const auto& md = ctx->client_metadata();
    const auto it = md.find("authorization");
    const std::string given =
        it == md.end() ? "" : std::string(it->second.data(), it->second.size());
    if (token_.empty() || !same(given, "Bearer " + token_)) {
      return {grpc::StatusCode::UNAUTHENTICATED,
              "a TCP client must send the daemon's token (STATE_DIR/token)"};
    }
  }
  try {
    body();
    return grpc::Status::OK;
  } catch (const RequestError& e) {
    return {code_of(e.kind), e.what()};
  } catch (const std::exception& e) {
    spdlog::error("request from {} failed: {}", ctx->peer(), e.what());
    return {grpc::StatusCode::INTERNAL, fmt::format("internal error: {}", e.what())};
  }
}

grpc::Status SchedulerService::SubmitCase(grpc::ServerContext* ctx,
                                          const v1::SubmitCaseRequest* req, v1::Job* out) {
  return guarded(ctx, [&] {
    if (!(req->timeout_s() >= 0))
      throw RequestError(Kind::invalid_argument, "timeout_s must be >= 0");
    *out = scheduler_.submit_case(bundle_from_proto(req->source()), req->timeout_s());
  });
}

grpc::Status SchedulerService::SubmitOptimization(grpc::ServerContext* ctx,
                                                  const v1::SubmitOptimizationRequest* req,
                                                  v1::Optimization* out) {
  return guarded(ctx, [&] {
    if (!(req->timeout_s() >= 0))
      throw RequestError(Kind::invalid_argument, "timeout_s must be >= 0");
    *out = scheduler_.submit_optimization(bundle_from_proto(req->source()), req->timeout_s());
  });
}

grpc::Status SchedulerService::GetJob(grpc::ServerContext* ctx, const v1::IdRequest* req,
                                      v1::Job* out) {
  return guarded(ctx, [&] { *out = scheduler_.job(parse_id(req->id(), 'j')); });
}

grpc::Status SchedulerService::ListJobs(grpc::ServerContext* ctx, const v1::ListJobsRequest* req,
                                        v1::ListJobsResponse* out) {
  return guarded(ctx, [&] {
    StateStore::JobFilter f;
    if (!req->optimization_id().empty()) f.optimization_id = parse_id(req->optimization_id(), 'o');
    f.active_only = req->active_only();
    f.limit = limit_of(req->limit());
    for (auto& j : scheduler_.jobs(f)) *out->add_jobs() = std::move(j);
  });
}

grpc::Status SchedulerService::GetOptimization(grpc::ServerContext* ctx, const v1::IdRequest* req,
                                               v1::Optimization* out) {
  return guarded(ctx, [&] { *out = scheduler_.optimization(parse_id(req->id(), 'o'), true); });
}

grpc::Status SchedulerService::ListOptimizations(grpc::ServerContext* ctx,
                                                 const v1::ListOptimizationsRequest* req,
                                                 v1::ListOptimizationsResponse* out) {
  return guarded(ctx, [&] {
    for (auto& o : scheduler_.optimizations(limit_of(req->limit())))
      *out->add_optimizations() = std::move(o);
  });
}

grpc::Status SchedulerService::Watch(grpc::ServerContext* ctx, const v1::IdRequest* req,
                                     grpc::ServerWriter<v1::WatchEvent>* writer) {
  return guarded(ctx, [&] {
    const bool is_job = req->id().starts_with("j");
    const std::int64_t id = parse_id(req->id(), is_job ? 'j' : 'o');
    std::uint64_t seen = scheduler_.version();
    std::string last;
    for (;;) {
      v1::WatchEvent ev;
      v1::State state;
      if (is_job) {
        *ev.mutable_job() = scheduler_.job(id);
        state = ev.job().state();
      } else {
        *ev.mutable_optimization() = scheduler_.optimization(id, false);
        state = ev.optimization().state();
      }
      std::string now = ev.SerializeAsString();
      if (now != last) {
        if (!writer->Write(ev)) return;  // the watcher went away
        last = std::move(now);
      }
      if (terminal(state) || ctx->IsCancelled()) return;
      seen = scheduler_.wait_for_change(seen, std::chrono::milliseconds(1000));
      if (scheduler_.stopping()) {
        throw RequestError(RequestError::Kind::unavailable,
                           "the daemon is stopping; the job continues after its restart");
      }
    }
  });
}

grpc::Status SchedulerService::Cancel(grpc::ServerContext* ctx, const v1::IdRequest* req,
                                      v1::CancelResponse* out) {
  return guarded(ctx, [&] {
    const bool is_job = req->id().starts_with("j");
    out->set_jobs_cancelled(is_job ? scheduler_.cancel_job(parse_id(req->id(), 'j'))
                                   : scheduler_.cancel_optimization(parse_id(req->id(), 'o')));
  });
}

grpc::Status SchedulerService::Resume(grpc::ServerContext* ctx, const v1::IdRequest* req,
                                      v1::Optimization* out) {
  return guarded(ctx, [&] { *out = scheduler_.resume(parse_id(req->id(), 'o')); });
}

grpc::Status SchedulerService::ListResults(grpc::ServerContext* ctx,
                                           const v1::ListResultsRequest* req,
                                           v1::ListResultsResponse* out) {
  return guarded(ctx, [&] {
    for (auto& r : scheduler_.results(limit_of(req->limit()))) *out->add_results() = std::move(r);
  });
}

std::string SchedulerService::result_key(const std::string& id) {
  if (is_key(id)) return id;
  if (is_key_prefix(id)) return scheduler_.result_key_of_prefix(id);
  if (id.starts_with("j")) return scheduler_.result_key_of_job(parse_id(id, 'j'));
  throw RequestError(Kind::invalid_argument,
                     fmt::format("'{}' is neither a job id (j<number>) nor a result key (64 hex "
                                 "digits, or at least the first 6)",
                                 id.substr(0, 80)));
}

grpc::Status SchedulerService::GetResult(grpc::ServerContext* ctx, const v1::IdRequest* req,
                                         v1::Result* out) {
  return guarded(ctx, [&] { *out = scheduler_.result(result_key(req->id()), true); });
}

grpc::Status SchedulerService::ExportResult(grpc::ServerContext* ctx, const v1::IdRequest* req,
                                            grpc::ServerWriter<v1::FileChunk>* writer) {
  return guarded(ctx, [&] {
    const std::string key = result_key(req->id());
    scheduler_.result(key, false);  // verified, or not_found / failed_precondition
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(scheduler_.result_dir(key))) {
      if (e.is_regular_file()) files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    constexpr std::size_t kChunk = 1 << 16;
    for (const auto& f : files) {
      std::ifstream in(f, std::ios::binary);
      std::string buffer(kChunk, '\0');
      for (;;) {
        in.read(buffer.data(), static_cast<std::streamsize>(kChunk));
        const auto n = static_cast<std::size_t>(in.gcount());
        const bool last = n < kChunk;  // (an empty last chunk ends a file of whole chunks)
        v1::FileChunk chunk;
        chunk.set_path(f.filename().string());
        chunk.set_data(buffer.data(), n);
        chunk.set_last(last);
        if (!writer->Write(chunk)) return;
        if (last) break;
      }
    }
  });
}

grpc::Status SchedulerService::Status(grpc::ServerContext* ctx, const v1::StatusRequest*,
                                      v1::DaemonStatus* out) {
  return guarded(ctx, [&] { *out = scheduler_.status(); });
}

grpc::Status SchedulerService::Shutdown(grpc::ServerContext* ctx, const v1::ShutdownRequest* req,
                                        v1::ShutdownResponse*) {
  return guarded(ctx, [&] { shutdown_(req->drain()); });
}

}  // namespace auvloop::scheduler
