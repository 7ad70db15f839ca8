// SPDX-License-Identifier: GPL-3.0-or-later
// Validated TOML reading: every problem is reported with file:line:column, field and reason.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>

#include "auvloop/geometry/file_io.hpp"
#include "auvloop/geometry/input.hpp"
#include "temp_dir.hpp"

using auvloop::input::Document;
using auvloop::input::InputError;
using auvloop::input::Range;
using ::testing::HasSubstr;

namespace {

std::string errors_of(const std::string& text, auto&& read) {
  try {
    auto doc = Document::parse(text, "case.toml");
    auto root = doc.root();
    read(root);
    root.finish();
    doc.check();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Input, ReadsValuesAndConvertsDegrees) {
  auto doc =
      Document::parse("x = 2\ny = 1.5\nangle = 90\nname = \"a\"\n[t]\nk = [1, 2]\n", "f.toml");
  auto root = doc.root();
  EXPECT_DOUBLE_EQ(root.number("x", Range::positive(), "m"), 2.0);  // integers are numbers
  EXPECT_DOUBLE_EQ(root.number("y", Range::positive(), "m"), 1.5);
  EXPECT_NEAR(root.angle("angle", Range::closed(0, 180)), 1.5707963267948966, 1e-15);
  EXPECT_EQ(root.text("name"), "a");
  auto t = root.table("t");
  EXPECT_EQ(t.numbers("k", 2, 2, Range::any(), ""), (std::vector<double>{1, 2}));
  EXPECT_DOUBLE_EQ(root.number_or("absent", 7.0, Range::any(), ""), 7.0);
  t.finish();
  root.finish();
  EXPECT_NO_THROW(doc.check());
}

TEST(Input, OutOfRangeNamesFileLineFieldValueAndRange) {
  const auto e = errors_of("[hull]\nd = -0.2\n", [](auto& root) {
    root.table("hull").number("d", Range::positive(), "m");
  });
  EXPECT_THAT(e, HasSubstr("case.toml:2:1: hull.d: value -0.2 is out of range: must be > 0 m"));
}

TEST(Input, WrongTypeIsReported) {
  const auto e = errors_of("span = \"long\"\n",
                           [](auto& root) { root.number("span", Range::positive(), "m"); });
  EXPECT_THAT(e, HasSubstr("case.toml:1:1: span: expected a number, got a string ('long')"));
}

TEST(Input, UnknownKeyGetsSuggestion) {
  const auto e = errors_of("spn = 1.0\n",
                           [](auto& root) { root.number_or("span", 1.0, Range::positive(), "m"); });
  EXPECT_THAT(e, HasSubstr("case.toml:1:1: spn: unknown key (did you mean \"span\"?)"));
}

TEST(Input, MissingKeyNamesTheTable) {
  const auto e = errors_of("[fins]\nspan = 1\n", [](auto& root) {
    auto t = root.table("fins");
    t.number("span", Range::positive(), "m");
    t.number("root_chord", Range::positive(), "m");
    t.finish();
  });
  EXPECT_THAT(
      e,
      HasSubstr("case.toml:1:2: fins.root_chord: missing required key (expected a number, > 0 m)"));
}

TEST(Input, AllProblemsReportedInFileOrder) {
  const auto e = errors_of("b = -1\na = \"x\"\nc = 3\n", [](auto& root) {
    root.number("a", Range::any(), "");
    root.number("b", Range::positive(), "");
  });
  const auto a = e.find(":1:1: b:");
  const auto b = e.find(":2:1: a:");
  const auto c = e.find(":3:1: c: unknown key");
  ASSERT_NE(a, std::string::npos) << e;
  ASSERT_NE(b, std::string::npos) << e;
  ASSERT_NE(c, std::string::npos) << e;
  EXPECT_LT(a, b);
  EXPECT_LT(b, c);
}

TEST(Input, ArrayElementErrorsPointAtTheElement) {
  const auto e = errors_of("cg = [0.0,\n  \"z\", 0.1]\n",
                           [](auto& root) { root.numbers("cg", 3, 3, Range::any(), "m"); });
  EXPECT_THAT(e, HasSubstr("case.toml:2:3: cg[1]: expected a number"));
}

TEST(Input, ChoiceListsTheOptions) {
  const auto e = errors_of("plant = \"cfd2\"\n", [](auto& root) {
    root.choice("plant", {"derivative", "cfd"});
  });
  EXPECT_THAT(e, HasSubstr("\"cfd2\" is not allowed: must be one of \"derivative\", \"cfd\""));
}

TEST(Input, SyntaxErrorHasLocation) {
  try {
    Document::parse("a = 1\nb = = 2\n", "bad.toml");
    FAIL() << "expected a syntax error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.toml:2:"));
    EXPECT_THAT(e.what(), HasSubstr("TOML syntax error"));
  }
}

TEST(Input, MissingFileIsReported) {
  try {
    Document::load("/nonexistent/vehicle.toml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/vehicle.toml: no such file"));
  }
}

TEST(Input, RangeDescriptions) {
  EXPECT_EQ(Range::closed(0, 35).describe("deg"), "in [0, 35] deg");
  EXPECT_EQ(Range::open_closed(0, 1).describe(""), "in (0, 1]");
  EXPECT_FALSE(Range::any().contains(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_FALSE(Range::positive().contains(0.0));
  EXPECT_TRUE(Range::non_negative().contains(0.0));
}

// Atomic writes (geometry/file_io.hpp): the target is replaced whole, no temporary file is left
// beside it, and a target in a missing directory is an error naming it.
TEST(FileIo, WriteFileAtomicallyReplacesWholeAndLeavesNothingBehind) {
  auvloop::test::TempDir tmp;
  const auto file = tmp.path() / "out.txt";
  auvloop::write_file_atomically(file, "first, the longer one");
  auvloop::write_file_atomically(file, "second");
  EXPECT_EQ(auvloop::read_file_text(file), "second");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(tmp.path())) ++entries;
  EXPECT_EQ(entries, 1);
  try {
    auvloop::write_file_atomically(tmp.path() / "missing" / "out.txt", "x");
    ADD_FAILURE() << "wrote into a missing directory";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing/out.txt"));
  }
}
