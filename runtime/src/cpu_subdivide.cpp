// CPU subdivision: the edge-point and vertex-point kernels of paper 3.1, one output
// vertex at a time, in the operation order the compute shaders use.
#include "looptess/runtime.h"
#include "subdivide_rules.h"

#include <cassert>
#include <cmath>

namespace lt {

SmoothLimitWeights loopSmoothLimitWeights(uint32_t valence) {
    // As OpenSubdiv's Sdc computes them (assignSmoothLimitMask and
    // assignSmoothLimitTangentMasks), in double, rounded once.
    SmoothLimitWeights w;
    double n = double(valence);
    if (valence == 6) {
        w.position = float(1.0 / 12.0);
    } else {
        double beta = 0.25 * std::cos(2.0 * M_PI / n) + 0.375;
        double gamma = (0.625 - beta * beta) / n;
        w.position = float(1.0 / (n + 3.0 / (8.0 * gamma)));
    }
    w.tangentU.resize(valence);
    w.tangentV.resize(valence);
    for (uint32_t k = 0; k < valence; ++k) {
        double a = 2.0 * M_PI * double(k) / n;
        double c = std::cos(a), s = std::sin(a);
        w.tangentU[k] = std::fabs(c) < 1e-12 ? 0.0f : float(c);  // exact zeros, as Sdc's valence-6 table
        w.tangentV[k] = std::fabs(s) < 1e-12 ? 0.0f : float(s);
    }
    return w;
}

SmoothWeights loopSmoothWeights(uint32_t valence) {
    // As OpenSubdiv's Sdc computes them: beta from cos(2 pi / n) in double.
    if (valence == 6) return {0.625f, 0.0625f};
    double n = double(valence);
    double beta = 0.25 * std::cos(2.0 * M_PI / n) + 0.375;
    double edge = (0.625 - beta * beta) / n;
    return {float(1.0 - edge * n), float(edge)};
}

namespace {

void refineLevel(const Refinement& r, float* v) {
    float* out = v + size_t(r.firstVertex) * 3;
    size_t mask = 0;
    for (uint32_t i = 0; i < r.vertexPointCount(); ++i) {
        uint32_t begin = r.vertexRingStart[i], end = r.vertexRingStart[i + 1];
        const float* parent = v + size_t(r.vertexParent[i]) * 3;
        bool masked = mask < r.maskedVertex.size() && r.maskedVertex[mask] == i;
        const float* w = masked ? &r.maskWeights[r.maskStart[mask]] : nullptr;
        SmoothWeights sw = masked ? SmoothWeights{} : loopSmoothWeights(end - begin);
        // Masks are affine (weights sum to 1): v' = v + sum w_j (ring_j - v). Summing
        // differences keeps the rounding relative to the ring's size, not to the
        // coordinates, which matters at high valence (OpenSubdiv's pole360).
        for (int k = 0; k < 3; ++k) {
            float sum = 0.0f;
            for (uint32_t j = begin; j < end; ++j)
                sum = sum + (masked ? w[j - begin] : sw.edge) * (v[size_t(r.vertexRing[j]) * 3 + k] - parent[k]);
            out[size_t(i) * 3 + k] = parent[k] + sum;
        }
        if (masked) ++mask;
    }
    out += size_t(r.vertexPointCount()) * 3;
    size_t crease = 0;
    for (uint32_t i = 0; i < r.edgePointCount(); ++i) {
        const uint32_t* e = &r.edgeVerts[size_t(i) * 4];
        float w = 0.0f;
        if (crease < r.creaseEdge.size() && r.creaseEdge[crease] == i) w = r.creaseWeight[crease++];
        EdgeWeights ew = edgeWeights(w);
        for (int k = 0; k < 3; ++k) {
            float ends = v[size_t(e[0]) * 3 + k] + v[size_t(e[1]) * 3 + k];
            float opposite = v[size_t(e[2]) * 3 + k] + v[size_t(e[3]) * 3 + k];
            out[size_t(i) * 3 + k] = ew.ends * ends + ew.opposite * opposite;
        }
    }
}

// Hierarchical edits of one level (asset.h VertexEdits), values from `value`
// (3 per edit of this level): one edited vertex at a time, its edits in order.
void applyEdits(const VertexEdits& e, const float* value, float* v) {
    for (size_t i = 0; i < e.vertex.size(); ++i) {
        float* p = v + size_t(e.vertex[i]) * 3;
        for (uint32_t k = e.start[i]; k < e.start[i + 1]; ++k) {
            const float* x = value + size_t(k) * 3;
            for (int c = 0; c < 3; ++c) {
                switch (e.op[k]) {
                case EditOp::Set: p[c] = x[c]; break;
                case EditOp::Add: p[c] = p[c] + x[c]; break;
                case EditOp::Subtract: p[c] = p[c] - x[c]; break;
                }
            }
        }
    }
}

}  // namespace

std::vector<float> bakedEditValues(const Asset& asset) {
    std::vector<float> values;
    for (const Level& level : asset.levels)
        values.insert(values.end(), level.edits.value.begin(), level.edits.value.end());
    return values;
}

void subdivideCpu(const Asset& asset, const float* controlPositions, uint32_t depth, std::vector<float>& vertices,
                  const float* editValues) {
    assert(depth <= asset.maxDepth());
    vertices.assign(size_t(asset.totalVertexCount()) * 3, 0.0f);
    std::copy(controlPositions, controlPositions + asset.positions.size(), vertices.begin());
    size_t edit = 0;  // first edit of level l in the flat order
    for (uint32_t l = 0; l <= depth; ++l) {
        const Level& level = asset.levels[l];
        if (l >= 1) refineLevel(level.refinement, vertices.data());
        const float* value = editValues ? editValues + edit * 3 : level.edits.value.data();
        if (level.edits.count()) applyEdits(level.edits, value, vertices.data());
        edit += level.edits.count();
    }
}

}  // namespace lt
