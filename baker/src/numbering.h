// Private to the baker: steps 2 and 3 of lt::bake (bake.cpp), the refined vertices
// the tables keep and their global numbering, each pass per candidate, vertex or
// edge over the threads (parallel.h), the result the same for every thread count.
#pragma once

#include "patches.h"

#include "looptess/asset.h"

#include <atomic>
#include <memory>
#include <vector>

namespace lt {

// Faces or vertices a thread range takes at least (parallel.h): each costs a
// fraction of a microsecond to a few.
constexpr size_t kFaceGrain = 1024;

// A face of a level that the tables draw or refine (step 1): a patch when regular.
// The patch points of a level's regular candidates are kept beside them, in
// candidate order (most of a deep level's candidates are irregular: 52 bytes each
// saved there).
struct Candidate {
    OsdIndex face;
    PatchParam param;
    bool regular = false;
};

// Per level: vertex -> nonzero when the tables need it. Bytes that several threads
// mark at once: only zero or not is read once a pass is over, so the result does not
// depend on the order.
using NeededVertices = std::vector<std::unique_ptr<std::atomic<uint8_t>[]>>;

// Step 2: the vertices of levels 0 .. levels - 1 that `candidates` need (a regular
// candidate's patch points, `points`, an irregular one's corners with their 1-rings
// for their limit stencils), closed downwards: a needed vertex of level l needs what
// its vertex or edge rule reads at level l - 1. An Internal error names the first
// vertex or edge (by level, then index) whose ring is incomplete.
Status collectNeeded(const Topology& topology, int levels, const std::vector<std::vector<Candidate>>& candidates,
                     const std::vector<std::vector<PatchPoints>>& points, size_t threads, NeededVertices& needed);

struct Numbering {
    std::vector<std::vector<uint32_t>> global;  // per level: vertex -> global index (~0u: not kept)
    std::vector<std::vector<OsdIndex>> order;   // per level: kept vertices in order
    std::vector<uint32_t> pointCount;           // per level: how many are vertex points
};

// Step 3: level 0 keeps every vertex; level l its needed vertex points, by their
// parent's global index, then its needed edge points, by their parent edge's
// smaller end's global index, then the larger's.
void number(const Topology& topology, int levels, const NeededVertices& needed, size_t threads, Numbering& out);

}  // namespace lt
