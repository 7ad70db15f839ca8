// SPDX-License-Identifier: GPL-3.0-or-later
// The socket directory check: a directory someone else could write to (or owns) is refused, so a
// fake daemon cannot be slipped in front of the client.
#include <sys/stat.h>

#include <filesystem>

#include <gtest/gtest.h>

#include "auvloop/scheduler/paths.hpp"

namespace auvloop::test {
namespace {
namespace fs = std::filesystem;

class SocketDirectory : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("auvloop-paths-" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path dir(const std::string& name, mode_t mode) {
    const fs::path d = root_ / name;
    fs::create_directory(d);
    ::chmod(d.c_str(), mode);
    return d;
  }
  fs::path root_;
};

TEST_F(SocketDirectory, OwnerOnlyAndStickyDirectoriesAreAccepted) {
  EXPECT_NO_THROW(scheduler::check_socket_directory(dir("private", 0700) / "s.sock"));
  EXPECT_NO_THROW(scheduler::check_socket_directory(dir("sticky", 01777) / "s.sock"));
  EXPECT_NO_THROW(scheduler::check_socket_directory(root_ / "not-yet" / "s.sock"));
}

TEST_F(SocketDirectory, WritableByOthersOrALinkIsRefusedWithTheReason) {
  try {
    scheduler::check_socket_directory(dir("open", 0777) / "s.sock");
    ADD_FAILURE() << "a world-writable directory was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("writable by other users"), std::string::npos) << e.what();
  }
  EXPECT_THROW(scheduler::check_socket_directory(dir("group", 0770) / "s.sock"),
               std::runtime_error);
  fs::create_directory_symlink(dir("target", 0700), root_ / "link");
  try {
    scheduler::check_socket_directory(root_ / "link" / "s.sock");
    ADD_FAILURE() << "a symbolic link was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("symbolic link"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace auvloop::test
