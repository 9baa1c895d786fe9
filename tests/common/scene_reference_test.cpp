// The rule for files a farm task's scene references: inside its directory.
#include "common/scene_reference.h"

#include <gtest/gtest.h>

#include <string>

namespace vesper {
namespace {

TEST(SceneReference, OnlyPathsThatStayInsideTheSceneDirectoryPass) {
  for (const char* inside :
       {"cube.obj", "assets/cube.obj", "./a/b.vdb", "a..b/c..", "..a/b", "smoke.####.vdb", "a/./b"})
    EXPECT_EQ(outside_reference_problem(inside), "") << inside;
  for (const char* outside : {"/etc/passwd", "/", "..", "../x.exr", "a/../../x", "a/..", "./../x",
                              "assets/../../../home/u/.ssh/id_rsa"})
    EXPECT_NE(outside_reference_problem(outside), "") << outside;
  EXPECT_NE(outside_reference_problem("/abs").find("absolute"), std::string::npos);
  EXPECT_NE(outside_reference_problem("a/../..").find("'..'"), std::string::npos);
  EXPECT_NE(outside_reference_problem(std::string("a\0/../x", 7)), "");
}

}  // namespace
}  // namespace vesper
