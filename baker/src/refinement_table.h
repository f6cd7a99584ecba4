// Private to the baker: the refinement table of one level (asset.h's Refinement),
// how each kept vertex of level l is computed from level l - 1.
#pragma once

#include "refine.h"

#include "looptess/asset.h"

#include <cstdint>
#include <vector>

namespace lt {

// Fills `r` (empty) for level `l` >= 1: `order`, the level's kept vertices, the
// first `points` of them vertex points, then edge points; `parentGlobal` and
// `global`, levels l - 1 and l's vertex -> global index. Vertex rings start at the
// neighbour with the smallest global index, so that the sums' order does not depend
// on OpenSubdiv's numbering. Runs on `threads` threads (at least 1), the same table
// for every count. Internal when a kept vertex reads one that was not kept.
Status buildRefinement(const Topology& topology, int l, const std::vector<uint32_t>& parentGlobal,
                       const std::vector<uint32_t>& global, const std::vector<OsdIndex>& order, uint32_t points,
                       size_t threads, Refinement& r);

}  // namespace lt
