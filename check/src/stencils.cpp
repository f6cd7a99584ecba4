// Limit stencils against OpenSubdiv (check A3 of looptess/tools/check.h).
//
// The asset's vertices of level l are matched to OpenSubdiv's through the tables:
// a vertex point is the child of its parent's match, an edge point the child of the
// edge between its ends' matches (edgeVerts a, b). Level 0 is the control mesh,
// the source's vertices in order (compareControlMesh has passed).
#include "check_internal.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace lt {
namespace {

// Each stencil of level l that an irregular face's corner uses: the first such
// corner's (base face, u, v).
struct CornerAt {
    uint32_t face;
    double u, v;
};
std::map<uint32_t, CornerAt> stencilCorners(const Level& level) {
    // Corner c of a patch at (s, t) = (0,0), (1,0), (0,1) (asset.h, PatchParam).
    static const double st[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    std::map<uint32_t, CornerAt> out;
    for (const IrregularFace& f : level.irregular) {
        const double d = std::ldexp(1.0, -int(f.param.level)), sign = f.param.rotated ? -1 : 1;
        for (int c = 0; c < 3; ++c)
            out.emplace(f.corners[c], CornerAt{f.param.baseFace, d * (f.param.ui + sign * st[c][0]),
                                               d * (f.param.vi + sign * st[c][1])});
    }
    return out;
}

double ulp(float w) {
    const float a = std::fabs(w);
    return double(std::nextafter(a, INFINITY)) - double(a);
}

}  // namespace

Status checkStencils(const Asset& asset, const InputMesh& source, StencilResult& out) {
    out = StencilResult{};
    if (asset.editCount() > 0) {
        out.skipped = "hierarchical edits (the levels' points are edited)";
        return Status::ok();
    }
    bool any = false;
    for (const Level& level : asset.levels) any = any || !level.limit.masked.empty();
    if (!any) return Status::ok();
    // Deep enough for every semi-sharp edge and vertex to decay (at most one level per
    // unit of sharpness; 10 and above is infinitely sharp), so that each stencil's
    // vertex reaches a level whose rule no longer changes; no deeper, since refining
    // along infinitely sharp creases grows with every level.
    float semi = 0;
    for (const InputMesh::Crease& c : source.creases) semi = c.sharpness < 10 ? std::max(semi, c.sharpness) : semi;
    for (const InputMesh::Corner& c : source.corners) semi = c.sharpness < 10 ? std::max(semi, c.sharpness) : semi;
    const int depth = std::min(10, std::max(int(asset.maxDepth()), int(std::ceil(semi)) + 1));
    OsdRefinedVertices osd;
    if (Status st = osd.build(source, depth); !st) return st;

    std::vector<int> match(asset.totalVertexCount(), -1);  // OpenSubdiv's vertex of its level
    for (uint32_t v = 0; v < asset.controlVertexCount(); ++v) match[v] = int(v);
    for (size_t l = 1; l < asset.levels.size(); ++l) {
        const Refinement& r = asset.levels[l].refinement;
        const uint32_t first = r.firstVertex;
        for (uint32_t i = 0; i < r.vertexPointCount(); ++i)
            match[first + i] = osd.vertexChild(int(l), match[r.vertexParent[i]]);
        for (uint32_t i = 0; i < r.edgePointCount(); ++i)
            match[first + r.vertexPointCount() + i] =
                osd.edgeChild(int(l), match[r.edgeVerts[4 * i]], match[r.edgeVerts[4 * i + 1]]);
    }

    for (size_t l = 0; l < asset.levels.size(); ++l) {
        const LimitStencils& s = asset.levels[l].limit;
        if (s.masked.empty()) continue;
        const std::map<uint32_t, CornerAt> corners = stencilCorners(asset.levels[l]);
        for (size_t k = 0; k < s.masked.size(); ++k) {
            const uint32_t stencil = s.masked[k];
            const auto at = corners.find(stencil);
            if (at == corners.end()) continue;  // no corner uses it
            const uint32_t v = s.vertex[stencil];
            double p[3];
            bool matched = match[v] >= 0 && osd.limitPosition(int(l), match[v], p);
            for (uint32_t j = s.start[stencil]; j < s.start[stencil + 1]; ++j)
                matched = matched && match[s.ring[j]] >= 0;
            if (!matched) {
                ++out.unmatched;
                continue;
            }
            const double* q = osd.vertex(int(l), match[v]);
            double sum[3] = {q[0], q[1], q[2]}, bound = 0, scale = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
            for (uint32_t j = s.start[stencil], w = s.maskStart[k]; j < s.start[stencil + 1]; ++j, ++w) {
                const double* r = osd.vertex(int(l), match[s.ring[j]]);
                const double d[3] = {r[0] - q[0], r[1] - q[1], r[2] - q[2]};
                const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                for (int c = 0; c < 3; ++c) sum[c] += double(s.position[w]) * d[c];
                bound += ulp(s.position[w]) * length;
                scale += length;
            }
            bound += 1e-12 * scale;
            const double e = std::sqrt((sum[0] - p[0]) * (sum[0] - p[0]) + (sum[1] - p[1]) * (sum[1] - p[1]) +
                                       (sum[2] - p[2]) * (sum[2] - p[2]));
            ++out.checked;
            out.worstRatio = std::max(out.worstRatio, e / bound);
            if (e <= bound) continue;
            if (out.failures++ == 0) {
                char text[256];
                std::snprintf(text, sizeof text,
                              "levels[%zu] stencil %u (vertex %u; face %u (u, v) = (%.9g, %.9g)): its position is %.3g "
                              "from OpenSubdiv's limit, %.3g times what its weights' rounding allows",
                              l, stencil, v, at->second.face, at->second.u, at->second.v, e, e / bound);
                out.firstFailure = text;
            }
        }
    }
    return Status::ok();
}

}  // namespace lt
