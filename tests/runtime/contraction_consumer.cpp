// tests/runtime/contraction_consumer.cpp -- an engine's translation unit: compiled
// with -ffp-contract=fast -mfma -O2 (tests/runtime/CMakeLists.txt), the flags the
// project's own targets never use, so that any surface arithmetic the runtime's
// public headers inline here would be fused and give other bits than the library's
// (test_contraction.cpp compares). No GoogleTest, only the public headers.
#include "contraction_calls.h"

#include "looptess/asset.h"
#include "looptess/runtime.h"

#include "contraction_calls.inc"

namespace lt::test {

void callsAsAnEngine(const ContractionInputs& in, ContractionOutputs& out) { callEverything(in, out); }

}  // namespace lt::test
