// Private to the baker: where hierarchical edits are, and which faces must be
// refined so that the edit levels' patches exist (docs/hierarchical-edits.md).
//
// An edit of vertex v at level k changes the limit surface over the level-k faces
// that touch v or one of its neighbours (the support of v's basis function: a
// face's 12 box-spline points are the vertices of the faces sharing a vertex with
// it). Those faces must be patches of level k or finer, so their parents at level
// k - 1 are refined:
//
//   Ref[k-1] = parents of { level-k faces touching v or a neighbour of v }
//   Ref[j-1] = parents of { level-j faces sharing a vertex with a face of Ref[j] }
//
// The second line keeps every face next to a refined face refined one level
// coarser too, so a patch borders patches at most one level finer and the NPP
// split patterns apply as for Far's features. A refined face that is regular is
// an irregular face (IPP) of its level, as the paper tags edited regions (4.3).
//
//        level k-1                       level k
//     +-------+-------+            +---+---+---+---+
//      \ Ref / \ Ref /              \ / \ / \ / \ /      v: the edited vertex
//       \   /   \   /                +---v---+---+       its faces and its
//        +-------+                    \ / \ / \ /        neighbours' faces must
//                                      +---+---+         be level-k patches
#pragma once

#include "refine.h"

#include <vector>

namespace lt {

struct EditRegion {
    struct Site {
        int level = 0;         // the edit's level k
        OsdIndex vertex = -1;  // in topology.level(k)
    };
    std::vector<Site> sites;                   // per InputMesh edit
    std::vector<std::vector<uint8_t>> refine;  // per level < K: face -> must be refined
};

// Resolves every edit's path in `topology` (whose uniform levels reach the deepest
// edit) and marks the faces to refine. BadInput, naming the edits, when a `set`
// shares its vertex with another edit (their order would decide the result).
Status planEdits(const InputMesh& mesh, const Topology& topology, const std::string& name, EditRegion& region);

// Fills each level's VertexEdits from the sites: `global[l][v]` is the global index
// of vertex v of level l (~0u when not kept). Edits of one vertex keep input order.
// BadInput when an edited vertex is not kept (nothing drawn reads it).
Status fillEdits(const InputMesh& mesh, const EditRegion& region, const std::vector<std::vector<uint32_t>>& global,
                 const std::string& name, std::vector<Level>& levels);

// "face 7 path 1 3 vertex 2": an edit as the OBJ tag names it, for messages.
std::string editName(const InputMesh::VertexEdit& edit);

}  // namespace lt
