// The one addition of the tests' build of the command (uwbsar_with_test_hooks: tools/main.cc and
// this file): before main, UWBSAR_TEST_INTERRUPT_COMMIT=<step>:<kill|int> arms the commit
// interruption (test/core/commit_interrupt.h), so that test/slam/session/session_safety_cli_test.cc
// can kill a real `uwbsar map --resume` at every step of its commit. The shipped uwbsar has no
// hook.
#include <cstdlib>

#include "test/core/commit_interrupt.h"

namespace {

[[maybe_unused]] const bool armed = uwbsar::testing::InterruptCommitAsSpecified(
    std::getenv(uwbsar::testing::kInterruptCommitVariable));

}  // namespace
