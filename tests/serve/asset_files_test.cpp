// SPDX-License-Identifier: GPL-3.0-or-later
#include "serve/asset_files.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace roifem::serve {
namespace {

namespace fs = std::filesystem;

TEST(AssetFiles, ServesThePagesFilesAndNothingOutsideThem) {
  test::TempDir dir;
  fs::create_directories(dir / "page/sub");
  fs::create_directories(dir / "lib/build");
  test::write_file(dir / "page/index.html", "<html>");
  test::write_file(dir / "page/app.js", "x");
  test::write_file(dir / "page/sub/a.css", "y");
  test::write_file(dir / "page/.secret", "z");
  test::write_file(dir / "lib/build/three.module.js", "t");
  test::write_file(dir / "outside.txt", "no");
  fs::create_symlink(dir / "outside.txt", dir / "page/link.txt");  // points out of the root
  const AssetFiles assets({{"/", dir / "page"}, {"/three/", dir / "lib"}});
  const auto canonical = [](const fs::path& p) { return fs::canonical(p); };

  EXPECT_EQ(assets.resolve("/"), canonical(dir / "page/index.html"));
  EXPECT_EQ(assets.resolve("/app.js?v=2"), canonical(dir / "page/app.js"));
  EXPECT_EQ(assets.resolve("/sub/a.css"), canonical(dir / "page/sub/a.css"));
  EXPECT_EQ(assets.resolve("/three/build/three.module.js"), canonical(dir / "lib/build/three.module.js"));
  for (const char* refused :
       {"/../outside.txt", "/sub/../../outside.txt", "/%2e%2e/outside.txt", "/..%2foutside.txt", "/three/../outside.txt",
        "/three/build/../../outside.txt", "/.secret", "/link.txt", "/sub", "/sub/", "//etc/passwd", "/missing.js",
        "/app.js\\..\\x", "/etc/passwd", "/three/", "relative.js", "/app.js%00.html"})
    EXPECT_FALSE(assets.resolve(refused).has_value()) << refused;
}

TEST(AssetFiles, NamesTheTypesThePageUses) {
  EXPECT_EQ(AssetFiles::content_type("a/index.html"), "text/html; charset=utf-8");
  EXPECT_EQ(AssetFiles::content_type("three.module.js"), "text/javascript; charset=utf-8");
  EXPECT_EQ(AssetFiles::content_type("style.css"), "text/css; charset=utf-8");
  EXPECT_EQ(AssetFiles::content_type("x.bin"), "application/octet-stream");
}

}  // namespace
}  // namespace roifem::serve
