// SPDX-License-Identifier: GPL-3.0-or-later
// `auvloop validate` end to end on the quick Re = 100 cavity (Ghia's table through the CLI): the
// table and the JSON, exit code 0 when every row passes.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

using auvloop::test::run_cli;

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
