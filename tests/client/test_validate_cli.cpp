// SPDX-License-Identifier: GPL-3.0-or-later
// `auvloop validate`: the list, an unknown name, and one quick case end to end (table and JSON).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

using auvloop::test::run_cli;

TEST(ValidateCli, ListsTheImplementedCases) {
  const auto r = run_cli("validate --list");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  for (const char* name : {"mms", "taylor-green", "cavity-re100", "cavity-re1000"})
    EXPECT_NE(r.output.find(name), std::string::npos) << name;
}

TEST(ValidateCli, UnknownCaseIsAUsageError) {
  const auto r = run_cli("validate no-such-case");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("no-such-case"), std::string::npos);
}

TEST(ValidateCli, QuickCavityRe100PassesWithTableAndJson) {
  const auto table = run_cli("validate cavity-re100 --quick");
  EXPECT_EQ(table.exit_code, 0) << table.output;
  EXPECT_NE(table.output.find("tolerance"), std::string::npos) << table.output;
  const auto r = run_cli("validate cavity-re100 --quick --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  EXPECT_TRUE(j.at("pass").get<bool>());
  ASSERT_EQ(j.at("cases").size(), 1u);
  EXPECT_EQ(j.at("cases")[0].at("name"), "cavity-re100");
  EXPECT_EQ(j.at("cases")[0].at("rows").size(), 2u);
}
