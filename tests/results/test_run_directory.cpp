// SPDX-License-Identifier: GPL-3.0-or-later
// The result directory: complete files, a stable content hash, a CSV that reads back, and a
// replacement that never leaves a mix of old and new.
#include <fstream>

#include <gtest/gtest.h>

#include "auvloop/results/run_directory.hpp"
#include "temp_dir.hpp"

using namespace auvloop;

namespace {
results::RunReport report(double scale) {
  results::RunReport r;
  r.name = "test";
  r.canonical_case = {{"dt_s", 0.1}, {"name", "test"}};
  const auto t = r.series.add("t", "s");
  const auto psi = r.series.add("psi", "deg");
  for (int k = 0; k < 5; ++k) {
    r.series.push(t, 0.1 * k);
    r.series.push(psi, k == 2 ? std::nan("") : scale * k);
  }
  r.metrics = {{"itae_deg_s2", 1.5}};
  r.plant = "derivative";
  return r;
}
}  // namespace

TEST(RunDirectory, HashIsSha256OfTheCanonicalCase) {
  // SHA-256 test vector (FIPS 180-2): "abc".
  EXPECT_EQ(results::sha256_hex("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(results::content_hash({{"a", 1}, {"b", 2}}),
            results::content_hash({{"b", 2}, {"a", 1}}));
  EXPECT_NE(results::content_hash({{"a", 1}}), results::content_hash({{"a", 2}}));
}

TEST(RunDirectory, WritesReadsBackAndReplacesWhole) {
  test::TempDir tmp;
  const auto dir = tmp.path() / "run";
  const auto out = results::write_run_directory(dir, report(1.0));
  for (const char* f : {"manifest.json", "metrics.json", "timeseries.csv"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  }
  const auto back = results::read_run_directory(dir);
  EXPECT_EQ(back.manifest["status"], "completed");
  EXPECT_EQ(back.manifest["content_hash"], results::content_hash(report(1.0).canonical_case));
  EXPECT_EQ(back.series["psi"].unit, "deg");
  EXPECT_TRUE(std::isnan(back.series["psi"].values[2]));  // a missing value stays missing
  EXPECT_DOUBLE_EQ(back.series["psi"].values[4], 4.0);
  // A second write replaces the directory; no scratch directories are left beside it.
  results::write_run_directory(dir, report(2.0));
  EXPECT_DOUBLE_EQ(results::read_run_directory(dir).series["psi"].values[4], 8.0);
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(tmp.path())) ++entries;
  EXPECT_EQ(entries, 1U);
}

TEST(RunDirectory, DivergedRunsAreMarked) {
  test::TempDir tmp;
  auto r = report(1.0);
  r.failure = "the derivative plant diverged";
  results::write_run_directory(tmp.path() / "d", r);
  const auto back = results::read_run_directory(tmp.path() / "d");
  EXPECT_EQ(back.manifest["status"], "diverged");
  EXPECT_EQ(back.series.rows(), 5U);  // what was computed is kept
}

TEST(RunDirectory, DamagedKeptFlowCostsItsPicturesOnly) {
  test::TempDir tmp;
  auto r = report(1.0);
  r.fields = tmp.path() / "kept";
  std::filesystem::create_directories(r.fields);
  tmp.write("kept/snapshot_000100.json", "{ cut short");
  const auto out = results::write_run_directory(tmp.path() / "d", r, {.plots = false});
  ASSERT_TRUE(out.fields_warning);
  EXPECT_NE(out.fields_warning->find("snapshot_000100.json: damaged"), std::string::npos);
  const auto back = results::read_run_directory(tmp.path() / "d");
  EXPECT_EQ(back.manifest["status"], "completed");
  EXPECT_EQ(back.series.rows(), 5U);
}

TEST(RunDirectory, DamagedDirectoriesAreReported) {
  test::TempDir tmp;
  std::filesystem::create_directories(tmp.path() / "bad");
  tmp.write("bad/manifest.json", "{ not json");
  tmp.write("bad/metrics.json", "{}");
  EXPECT_THROW(results::read_run_directory(tmp.path() / "bad"), std::runtime_error);
  EXPECT_THROW(results::read_run_directory(tmp.path() / "missing"), std::runtime_error);
}
