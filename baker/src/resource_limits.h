// Private to the baker: resource-limit messages and the memory estimate.
//
// Every limit error reads
//   "<value> <what>, more than the limit of <limit> (raise it with <option>)"
// after the caller's "<file>: " (and line or glTF object) prefix, so a user sees the
// file, the value, the limit and the loopbake option in one line.
#pragma once

#include "looptess/tools/baker.h"

#include <opensubdiv/far/topologyLevel.h>

#include <cstdint>
#include <string>

namespace lt {

// "<value> <what>, more than the limit of <limit> (raise it with <option>)".
std::string limitMessage(const std::string& value, const std::string& what, uint64_t limit, const char* option);
inline std::string limitMessage(uint64_t value, const std::string& what, uint64_t limit, const char* option) {
    return limitMessage(std::to_string(value), what, limit, option);
}

// Upper estimate of adaptive refinement to `maxDepth` from the unrefined base level
// (limits.cpp says how, and what it was calibrated on). Fills the estimated fields.
// Levels 1..uniformDepth are refined everywhere (hierarchical edits: refine.h's
// Topology), so they count 4x their previous level.
void estimateMemory(const OpenSubdiv::Far::TopologyLevel& base, int maxDepth, int uniformDepth, MemoryStats& out);

// The depth to bake (bake's contract, looptess/tools/baker.h): an explicit
// settings.maxDepth is checked against the memory limit; 0 takes the deepest depth
// from max(kDefaultMaxDepth, editDepth) down to max(1, editDepth) whose estimates fit
// the memory and output limits, and says why in `reason`. `memory` gets the
// estimates of the depth chosen (or refused).
Status chooseDepth(const OpenSubdiv::Far::TopologyLevel& base, const BakeSettings& settings, int editDepth, int& depth,
                   MemoryStats& memory, std::string& reason);

}  // namespace lt
