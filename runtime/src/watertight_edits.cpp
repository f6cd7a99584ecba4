// Watertight rule 3 with hierarchical edits (watertight.h): the level-l vertices
// whose limit point the edits of level l move.
#include "watertight.h"

#include "sub_patches.h"

#include <algorithm>

namespace lt {
namespace {

// The 1-ring of a regular patch's corner c (point kPatchCorner[c]) in the patch's
// 12-point numbering, counter-clockwise from the corner's edge c. On the lattice of
// asset.h's RegularPatch, a point's six neighbours are left, right and the two
// above and below it:
//
//          10-----11
//          / \   / \           c0 = 4: 5 8 7 3 0 1
//         /   \ /   \          c1 = 5: 8 4 1 2 6 9
//        7-----8-----9         c2 = 8: 4 5 9 11 10 7
//       / \   / \   / \ .
//      /   \ /   \ /   \ .
//     3-----4-----5-----6
//      \   / \   / \   /
//       \ /   \ /   \ /
//        0-----1-----2
//
// Phantom points (boundaryMask) are stored as copies of point 4, which is either
// the corner itself or one of its real neighbours, so they add no false neighbour.
const uint8_t kCornerRing[3][6] = {{5, 8, 7, 3, 0, 1}, {8, 4, 1, 2, 6, 9}, {4, 5, 9, 11, 10, 7}};

}  // namespace

std::vector<uint32_t> editedLimitVertices(const Asset& asset, uint32_t l) {
    const VertexEdits& edits = asset.levels[l].edits;
    if (edits.vertex.empty()) return {};
    auto edited = [&](uint32_t v) { return std::binary_search(edits.vertex.begin(), edits.vertex.end(), v); };
    std::vector<uint32_t> out(edits.vertex);
    // A limit point moves when its vertex or a ring neighbour is edited (Loop's limit
    // masks read the vertex and its 1-ring). Every ring the tables know of level l.
    auto ring = [&](uint32_t centre, const uint32_t* begin, const uint32_t* end) {
        if (edited(centre))
            out.insert(out.end(), begin, end);
        else if (std::any_of(begin, end, edited))
            out.push_back(centre);
    };
    for (const RegularPatch& p : asset.levels[l].regular)
        for (int c = 0; c < 3; ++c) {
            uint32_t r[6];
            for (int j = 0; j < 6; ++j) r[j] = p.points[kCornerRing[c][j]];
            ring(p.points[kPatchCorner[c]], r, r + 6);
        }
    const LimitStencils& ls = asset.levels[l].limit;
    for (uint32_t k = 0; k < ls.count(); ++k)
        ring(ls.vertex[k], ls.ring.data() + ls.start[k], ls.ring.data() + ls.start[k + 1]);
    if (l + 1 < asset.levels.size()) {  // the next level's vertex points read their parent's ring
        const Refinement& r = asset.levels[l + 1].refinement;
        for (uint32_t i = 0; i < r.vertexPointCount(); ++i)
            ring(r.vertexParent[i], r.vertexRing.data() + r.vertexRingStart[i],
                 r.vertexRing.data() + r.vertexRingStart[i + 1]);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

}  // namespace lt
