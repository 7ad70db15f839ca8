// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzz target: what a client can make the daemon parse. The input is tried as an RPC request
// (SubmitCase / SubmitOptimization, protobuf wire format), as case and optimisation TOML text,
// and as a job / result id. Refusing the input with one of the documented errors is correct;
// anything else (another exception, a crash, a sanitizer report) is a bug.
//
// Built two ways: with libFuzzer (clang, AUVLOOP_FUZZ=ON, scripts/fuzz.sh) for coverage-guided
// runs, and with fuzz_driver.cpp (any compiler) for the short random-mutation run in CI.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "auvloop/geometry/input.hpp"
#include "auvloop/scheduler/bundle.hpp"
#include "auvloop/scheduler/scheduler.hpp"
#include "auvloop/scheduler/study.hpp"
#include "auvloop/v1/scheduler.pb.h"
#include "google/protobuf/stubs/logging.h"

namespace {
using namespace auvloop;

// Runs `parse`; the documented refusals are fine, anything else escapes to the fuzzer.
template <class F>
void refused_or_parsed(F&& parse) {
  try {
    parse();
  } catch (const input::InputError&) {
  } catch (const std::invalid_argument&) {
  } catch (const scheduler::RequestError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool quiet = [] {  // invalid UTF-8 is refused; no need to log each one
    google::protobuf::SetLogHandler(nullptr);
    return true;
  }();
  (void)quiet;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  v1::SubmitCaseRequest case_request;
  if (case_request.ParseFromString(bytes)) {
    refused_or_parsed(
        [&] { scheduler::parse_case_bundle(scheduler::bundle_from_proto(case_request.source())); });
  }
  v1::SubmitOptimizationRequest study_request;
  if (study_request.ParseFromString(bytes)) {
    refused_or_parsed([&] {
      scheduler::parse_study_bundle(scheduler::bundle_from_proto(study_request.source()));
    });
  }
  const scheduler::SourceBundle as_text{"fuzz.toml", bytes, {{"case.toml", bytes}}};
  refused_or_parsed([&] { scheduler::parse_case_bundle(as_text); });
  refused_or_parsed([&] { scheduler::parse_study_bundle(as_text); });
  refused_or_parsed([&] { scheduler::parse_id(bytes, 'j'); });
  refused_or_parsed([&] { scheduler::parse_id(bytes, 'o'); });
  return 0;
}
