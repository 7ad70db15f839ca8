// SPDX-License-Identifier: GPL-3.0-or-later
// `auvloop validate`: the list and an unknown name (fast; the end-to-end run of a case is in
// test_validate_cli_cases, label validation).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

using auvloop::test::run_cli;

TEST(ValidateCli, ListsTheImplementedCases) {
  const auto r = run_cli("validate --list");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  for (const char* name :
       {"mms", "mms-overset", "taylor-green", "cavity-re100", "cavity-re1000", "schaefer-turek-2d1",
        "schaefer-turek-2d1-overset", "schaefer-turek-2d2", "schaefer-turek-2d2-overset",
        "rotating-frame-at-rest", "galilean-cylinder", "pitching-foil"})
    EXPECT_NE(r.output.find(name), std::string::npos) << name;
}

TEST(ValidateCli, UnknownCaseIsAUsageError) {
  const auto r = run_cli("validate no-such-case");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no-such-case"), std::string::npos);
}
