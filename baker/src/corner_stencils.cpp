// corner_stencils.cpp -- the limit stencils of a level's IPP corners (corner_stencils.h).
#include "corner_stencils.h"

#include "face_corner.h"

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <tuple>

namespace lt {

Status buildCornerStencils(const Topology& topology, int l, int maxDepth, const StencilOrienter& orienter,
                           const std::vector<uint32_t>& g, const std::vector<OsdIndex>& faces, LimitStencils& ls,
                           std::vector<uint32_t>& cornerOf) {
    const Far::TopologyLevel& topo = topology.level(l);
    const Far::TopologyRefiner& refiner = topology.refiner(l);
    const int local = topology.local(l);
    struct Corner {
        uint32_t global;
        OsdIndex sector, own, vertex, face;  // own: the face whose corner is the stencil, or -1
        int ownLevel = kFaceCornerLevel;     // the level own's corner is refined to
        auto key() const { return std::make_tuple(global, sector, own); }
        bool operator<(const Corner& o) const { return key() < o.key(); }
        bool operator==(const Corner& o) const { return key() == o.key(); }
    };
    std::vector<Corner> corners, faceCorners;  // unique keys; the keys of each face's corners
    for (OsdIndex face : faces)
        for (OsdIndex v : topo.GetFaceVertices(face)) {
            // No tangent plane by topology: a spike whose limit lies below float
            // resolution; the face's corner at the deepest level drawn (spec).
            // A sheet's crease sector inside a non-manifold edge shares its first
            // face's corner, near its limit (level 24), bit for bit.
            OsdIndex own = -1, sheet;
            int ownLevel = maxDepth;
            if (sheetSector(refiner, local, v, face, sheet)) {
                own = sheet;
                ownLevel = kFaceCornerLevel;
            } else if (!tangentPlaneAt(refiner, local, v, face)) {
                own = face;
            }
            faceCorners.push_back({g[v], limitSector(refiner, local, v, face), own, v, face, ownLevel});
        }
    // The sectors' stencils; a slit's (no normal on the baked positions) gives
    // each of its faces one of its own.
    std::map<std::pair<uint32_t, OsdIndex>, LimitStencil> sectors;
    for (const Corner& corner : faceCorners) {
        auto [it, added] = sectors.emplace(std::make_pair(corner.global, corner.sector), LimitStencil{});
        if (added) limitStencil(refiner, local, corner.vertex, corner.face, it->second);
    }
    for (Corner& corner : faceCorners)
        if (corner.own < 0 &&
            orienter.degenerate(l, corner.vertex, corner.face, sectors.at({corner.global, corner.sector}))) {
            corner.own = corner.face;
            corner.ownLevel = kFaceCornerLevel;
        }
    // Orient the sector stencils that some face uses for its normal.
    std::set<std::pair<uint32_t, OsdIndex>> oriented;
    for (const Corner& corner : faceCorners)
        if (corner.own < 0 && oriented.insert({corner.global, corner.sector}).second)
            orienter.orient(l, sectors.at({corner.global, corner.sector}));
    corners = faceCorners;
    std::sort(corners.begin(), corners.end());
    corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
    ls.start.push_back(0);
    LimitStencil own;
    for (const Corner& corner : corners) {
        uint32_t index = ls.count();
        ls.vertex.push_back(corner.global);
        const LimitStencil* stencil = &sectors.at({corner.global, corner.sector});
        if (corner.own >= 0) {
            if (!orienter.faceStencil(l, corner.vertex, corner.own, corner.ownLevel, maxDepth, *stencil, own))
                return Status::error(Status::Internal, "OpenSubdiv refused the 1-ring of level " + std::to_string(l) +
                                                           " vertex " + std::to_string(corner.vertex));
            stencil = &own;
        }
        // Ring from the neighbour with the smallest global index; the vertex's own
        // weight (entry 0) is implied by affinity.
        size_t n = stencil->points.size() - 1, first = 0;
        for (size_t k = 1; k < n; ++k)
            if (g[stencil->points[1 + k]] < g[stencil->points[1 + first]]) first = k;
        for (size_t k = 0; k < n; ++k) ls.ring.push_back(g[stencil->points[1 + (first + k) % n]]);
        ls.start.push_back(uint32_t(ls.ring.size()));
        if (stencil->smooth) continue;
        if (ls.masked.empty()) ls.maskStart.push_back(0);
        ls.masked.push_back(index);
        for (size_t k = 0; k < n; ++k) {
            size_t w = 1 + (first + k) % n;
            ls.position.push_back(float(stencil->position[w]));
            ls.tangentU.push_back(float(stencil->tangentU[w]));
            ls.tangentV.push_back(float(stencil->tangentV[w]));
        }
        ls.maskStart.push_back(uint32_t(ls.position.size()));
    }
    cornerOf.clear();
    for (const Corner& corner : faceCorners)
        cornerOf.push_back(uint32_t(std::lower_bound(corners.begin(), corners.end(), corner) - corners.begin()));
    if (ls.count() == 0) ls.start.clear();
    return Status::ok();
}

}  // namespace lt
