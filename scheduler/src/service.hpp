// SPDX-License-Identifier: GPL-3.0-or-later
// The gRPC service: validates each request, calls the scheduler, maps errors onto status codes.
#pragma once

#include <atomic>
#include <functional>
#include <string>

#include "auvloop/scheduler/scheduler.hpp"
#include "auvloop/v1/scheduler.grpc.pb.h"

namespace auvloop::scheduler {

class SchedulerService final : public v1::Scheduler::Service {
 public:
  // `token`: required from TCP peers (empty: TCP is off); `shutdown` is called on a Shutdown
  // request, after the reply.
  SchedulerService(Scheduler& scheduler, std::string token, std::function<void(bool)> shutdown);

  grpc::Status SubmitCase(grpc::ServerContext*, const v1::SubmitCaseRequest*, v1::Job*) override;
  grpc::Status SubmitOptimization(grpc::ServerContext*, const v1::SubmitOptimizationRequest*,
                                  v1::Optimization*) override;
  grpc::Status GetJob(grpc::ServerContext*, const v1::IdRequest*, v1::Job*) override;
  grpc::Status ListJobs(grpc::ServerContext*, const v1::ListJobsRequest*,
                        v1::ListJobsResponse*) override;
  grpc::Status GetOptimization(grpc::ServerContext*, const v1::IdRequest*,
                               v1::Optimization*) override;
  grpc::Status ListOptimizations(grpc::ServerContext*, const v1::ListOptimizationsRequest*,
                                 v1::ListOptimizationsResponse*) override;
  grpc::Status Watch(grpc::ServerContext*, const v1::IdRequest*,
                     grpc::ServerWriter<v1::WatchEvent>*) override;
  grpc::Status Cancel(grpc::ServerContext*, const v1::IdRequest*, v1::CancelResponse*) override;
  grpc::Status Resume(grpc::ServerContext*, const v1::IdRequest*, v1::Optimization*) override;
  grpc::Status ListResults(grpc::ServerContext*, const v1::ListResultsRequest*,
                           v1::ListResultsResponse*) override;
  grpc::Status GetResult(grpc::ServerContext*, const v1::IdRequest*, v1::Result*) override;
  grpc::Status ExportResult(grpc::ServerContext*, const v1::IdRequest*,
                            grpc::ServerWriter<v1::FileChunk>*) override;
  grpc::Status Status(grpc::ServerContext*, const v1::StatusRequest*, v1::DaemonStatus*) override;
  grpc::Status Shutdown(grpc::ServerContext*, const v1::ShutdownRequest*,
                        v1::ShutdownResponse*) override;

 private:
  // Runs `body` after the authorisation check, turning exceptions into status codes.
  grpc::Status guarded(grpc::ServerContext* ctx, const std::function<void()>& body);
  std::string result_key(const std::string& id);

  Scheduler& scheduler_;
  std::string token_;
  std::function<void(bool)> shutdown_;
};

}  // namespace auvloop::scheduler
