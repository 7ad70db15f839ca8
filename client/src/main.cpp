// SPDX-License-Identifier: GPL-3.0-or-later
// auvloop: command-line entry point. Each subcommand family lives in its own *_commands.cpp.
#include <cstdio>
#include <exception>

#include <fmt/format.h>

#include "auvloop/geometry/error.hpp"
#include "auvloop/geometry/input.hpp"
#include "cli.hpp"
#include "daemon_connection.hpp"

namespace {
constexpr const char* kFooter = R"(Exit codes:
  0  success
  1  internal error (a bug: please report it)
  2  bad command line
  3  invalid input file (the message gives file:line:column and the field)
  4  the work failed (geometry impossible, file unreadable or unwritable, a job failed)
  5  no daemon answers (start one: auvloop daemon start)

Vehicles: a TOML file (docs/vehicle-file.md) or preset:NAME; without one, preset:remus100.
Units are SI; angles on the command line and in files are degrees.)";
}  // namespace

int main(int argc, char** argv) {
  using namespace auvloop;
  CLI::App app{"auvloop: CFD-in-the-loop design and tuning of AUV manoeuvring controllers",
               "auvloop"};
  app.footer(kFooter);
  app.require_subcommand(1);
  app.set_version_flag("--version", "auvloop 0.1.0");
  int exit_code = cli::kOk;
  cli::register_geometry_commands(app);
  cli::register_run_commands(app, exit_code);
  cli::register_optimize_command(app, exit_code);
  cli::register_daemon_commands(app, exit_code);
  cli::register_job_commands(app, exit_code);
  cli::register_results_commands(app, exit_code);
  cli::register_validate_command(app, exit_code);
  cli::register_mesh_command(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return cli::kUsage;
  } catch (const cli::DaemonUnavailable& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return cli::kUnavailable;
  } catch (const cli::RpcError& e) {
    fmt::print(stderr, "error: the daemon refused: {}\n", e.what());
    return e.code == grpc::StatusCode::INVALID_ARGUMENT ? cli::kBadInput : cli::kFailed;
  } catch (const input::InputError& e) {
    fmt::print(stderr, "error: invalid input:\n{}\n", e.what());
    return cli::kBadInput;
  } catch (const geometry::GeometryError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return cli::kFailed;
  } catch (const std::filesystem::filesystem_error& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return cli::kFailed;
  } catch (const std::invalid_argument& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return cli::kBadInput;
  } catch (const std::runtime_error& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return cli::kFailed;
  } catch (const std::exception& e) {
    fmt::print(stderr, "internal error: {}\n", e.what());
    return cli::kInternalError;
  }
  return exit_code;
}
