// SPDX-License-Identifier: GPL-3.0-or-later
// `auvloop validate [NAME...] [--quick] [--json] [--list]`: runs the CFD engine's verification and
// validation cases (engine/validation.hpp) and the CFD plant's trials (results/trials.hpp), and
// prints, per case, quantity, auvloop's value, the reference, the error, the tolerance and
// pass/fail. Exit 0 only when every row passes.
#include <algorithm>
#include <chrono>
#include <iostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "auvloop/engine/validation.hpp"
#include "auvloop/results/trials.hpp"
#include "cli.hpp"

namespace auvloop::cli {
namespace {
using nlohmann::json;
namespace validation = engine::validation;

struct ValidateOptions {
  std::vector<std::string> names;
  bool quick = false;
  bool json_output = false;
  bool list = false;
};

json to_json(const validation::Result& r, double seconds) {
  json rows = json::array();
  for (const auto& row : r.rows) {
    rows.push_back({{"quantity", row.quantity},
                    {"value", row.value},
                    {"reference", row.reference},
                    {"error", row.error},
                    {"tolerance", row.tolerance},
                    {"pass", row.pass}});
  }
  return {{"name", r.name},
          {"pass", r.pass()},
          {"rows", rows},
          {"notes", r.notes},
          {"seconds", seconds}};
}

void print_table(const validation::Result& r, double seconds) {
  fmt::print("{} ({:.1f} s): {}\n", r.name, seconds, r.pass() ? "PASS" : "FAIL");
  for (const auto& n : r.notes) fmt::print("  {}\n", n);
  fmt::print("  {:<30} {:>12} {:>12} {:>10} {:>10}  {}\n", "quantity", "auvloop", "reference",
             "error", "tolerance", "pass");
  for (const auto& row : r.rows) {
    fmt::print("  {:<30} {:>12.5g} {:>12.5g} {:>10.3g} {:>10.3g}  {}\n", row.quantity, row.value,
               row.reference, row.error, row.tolerance, row.pass ? "yes" : "NO");
  }
}

// The engine's cases, then the CFD plant's closed-loop trials (results/trials.hpp).
const std::vector<validation::Case>& all_cases() {
  static const auto all = [] {
    auto cases = validation::cases();
    for (auto& c : results::trial_cases()) cases.push_back(std::move(c));
    return cases;
  }();
  return all;
}

int run_validate(const ValidateOptions& o) {
  const auto& all = all_cases();
  if (o.list) {
    std::size_t width = 0;
    for (const auto& c : all) width = std::max(width, c.name.size());
    for (const auto& c : all) fmt::print("{:<{}}  {}\n", c.name, width, c.description);
    return kOk;
  }
  std::vector<const validation::Case*> chosen;
  for (const auto& name : o.names) {
    const validation::Case* found = nullptr;
    for (const auto& c : all)
      if (c.name == name) found = &c;
    if (found == nullptr) {
      fmt::print(stderr, "error: no validation case '{}' (auvloop validate --list)\n", name);
      return kUsage;
    }
    chosen.push_back(found);
  }
  if (chosen.empty())
    for (const auto& c : all) chosen.push_back(&c);
  bool pass = true;
  json out = json::array();
  for (const auto* c : chosen) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto result = c->run(o.quick);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    pass = pass && result.pass();
    if (o.json_output)
      out.push_back(to_json(result, s));
    else
      print_table(result, s);
  }
  if (o.json_output) std::cout << json{{"pass", pass}, {"cases", out}}.dump(2) << "\n";
  return pass ? kOk : kFailed;
}
}  // namespace

void register_validate_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ValidateOptions>();
  auto* cmd = app.add_subcommand(
      "validate",
      "Verify the CFD engine against exact solutions and published data (exit 0 only if all pass)");
  cmd->add_option("names", o->names, "Cases to run (default: all; see --list)");
  cmd->add_flag("--quick", o->quick, "CI-sized grids (seconds per case)");
  cmd->add_flag("--json", o->json_output, "Machine-readable output");
  cmd->add_flag("--list", o->list, "List the cases and exit");
  cmd->callback([o, &exit_code] { exit_code = run_validate(*o); });
}

}  // namespace auvloop::cli
