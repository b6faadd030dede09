// SPDX-License-Identifier: GPL-2.0
// The page's files are found, nothing outside --root is.
#include "advee/web/static_files.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace advee::web {
namespace {

namespace fs = std::filesystem;

class StaticFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    base_ = fs::temp_directory_path() / ("advee-web-test-" + std::to_string(::getpid()));
    fs::create_directories(base_ / "root" / "sub");
    std::ofstream(base_ / "root" / "index.html") << "<html>";
    std::ofstream(base_ / "root" / "dashboard.js") << "x";
    std::ofstream(base_ / "root" / "sub" / "a.css") << "y";
    std::ofstream(base_ / "secret.txt") << "no";
  }
  void TearDown() override { fs::remove_all(base_); }
  fs::path root() const { return base_ / "root"; }
  fs::path base_;
};

TEST_F(StaticFiles, RootIsIndex) {
  EXPECT_EQ(resolve_static(root(), "/"), root() / "index.html");
  EXPECT_EQ(resolve_static(root(), "/?x=1"), root() / "index.html");
  EXPECT_EQ(read_file(*resolve_static(root(), "/")), "<html>");
}

TEST_F(StaticFiles, FilesAndSubdirectories) {
  EXPECT_EQ(resolve_static(root(), "/dashboard.js"), root() / "dashboard.js");
  EXPECT_EQ(resolve_static(root(), "/sub/a.css"), root() / "sub" / "a.css");
  EXPECT_EQ(resolve_static(root(), "//sub/./a.css"), root() / "sub" / "a.css");
}

TEST_F(StaticFiles, NothingOutsideTheRoot) {
  EXPECT_FALSE(resolve_static(root(), "/../secret.txt"));
  EXPECT_FALSE(resolve_static(root(), "/sub/../../secret.txt"));
  EXPECT_FALSE(resolve_static(root(), "/%2e%2e/secret.txt"));
  EXPECT_FALSE(resolve_static(root(), "/..\\secret.txt"));
  EXPECT_FALSE(resolve_static(root(), "secret.txt"));
  EXPECT_FALSE(resolve_static(root(), "/missing.html"));
  EXPECT_FALSE(resolve_static(root(), "/sub"));  // directory without index.html
}

TEST_F(StaticFiles, ContentTypes) {
  EXPECT_EQ(content_type("index.html"), "text/html; charset=utf-8");
  EXPECT_EQ(content_type("dashboard.js"), "text/javascript; charset=utf-8");
  EXPECT_EQ(content_type("dashboard.css"), "text/css; charset=utf-8");
  EXPECT_EQ(content_type("x.bin"), "application/octet-stream");
}

TEST(StaticFilesShipped, ThePageIsComplete) {
  const fs::path dir = ADVEE_WEB_STATIC_DIR;
  for (const char* f : {"/", "/dashboard.js", "/dashboard.css"})
    EXPECT_TRUE(resolve_static(dir, f)) << f;
}

}  // namespace
}  // namespace advee::web
