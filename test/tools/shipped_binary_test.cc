// The shipped `uwbsar` holds no test hook (issue 46): the interruption tests' hook lives only in
// the test build of the command (uwbsar_with_test_hooks, test/tools/arm_commit_interrupt.cc),
// so no environment variable can make the robot's binary kill itself.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace uwbsar {
namespace {

/// Whether the file at `path` holds `text` anywhere in its bytes (what `strings | grep` sees).
bool BinaryHolds(const std::string& path, const std::string& text) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.good()) << path;
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str().find(text) != std::string::npos;
}

TEST(ShippedBinaryTest, HoldsNoTestHook) {
  EXPECT_FALSE(BinaryHolds(UWBSAR_BIN, "UWBSAR_TEST")) << UWBSAR_BIN;
  // The search does find the hook where it is: in the tests' build of the command.
  EXPECT_TRUE(BinaryHolds(UWBSAR_HOOKS_BIN, "UWBSAR_TEST_INTERRUPT_COMMIT")) << UWBSAR_HOOKS_BIN;
}

}  // namespace
}  // namespace uwbsar
