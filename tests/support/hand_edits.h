// Shared by the runtime edit tests (test_edits_runtime.cpp on the CPU,
// test_vulkan_edits.cpp on the GPU): hierarchical edits put into a baked asset by
// hand (asset.h's VertexEdits), at existing vertices of any level, so the runtime
// can be tested without the baker's edit support.
#pragma once

#include "looptess/asset.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace lt::test {

struct HandEdit {
    uint32_t level = 0, vertex = 0;  // vertex: global index of a vertex of `level`
    EditOp op = EditOp::Add;
    std::array<float, 3> value = {0, 0, 0};
};

// Replaces every level's edits by `edits`: grouped by vertex (increasing), each
// vertex's edits in the order given.
inline void setEdits(Asset& asset, const std::vector<HandEdit>& edits) {
    for (uint32_t l = 0; l < asset.levels.size(); ++l) {
        VertexEdits& e = asset.levels[l].edits;
        e = VertexEdits{};
        std::vector<uint32_t> vertices;
        for (const HandEdit& h : edits)
            if (h.level == l) vertices.push_back(h.vertex);
        std::sort(vertices.begin(), vertices.end());
        vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
        if (vertices.empty()) continue;
        e.start.push_back(0);
        for (uint32_t v : vertices) {
            e.vertex.push_back(v);
            for (const HandEdit& h : edits)
                if (h.level == l && h.vertex == v) {
                    e.op.push_back(h.op);
                    e.value.insert(e.value.end(), h.value.begin(), h.value.end());
                }
            e.start.push_back(uint32_t(e.op.size()));
        }
    }
}

// The first global vertex index of level l and one past its last.
inline std::pair<uint32_t, uint32_t> levelVertices(const Asset& asset, uint32_t l) {
    uint32_t begin = l == 0 ? 0 : asset.levels[l].refinement.firstVertex;
    uint32_t end = l + 1 < asset.levels.size() ? asset.levels[l + 1].refinement.firstVertex : asset.totalVertexCount();
    return {begin, end};
}

// Edits on every level 0..maxDepth that the drawn surface reads: per level, the
// corners of its first two regular patches (or, without any, its first limit
// stencils' vertices) get add / subtract / set sequences scaled by `size`.
inline std::vector<HandEdit> editsOnEveryLevel(const Asset& asset, float size) {
    std::vector<HandEdit> out;
    for (uint32_t l = 0; l < asset.levels.size(); ++l) {
        const Level& level = asset.levels[l];
        std::vector<uint32_t> picks;
        for (size_t k = 0; k < level.regular.size() && k < 2; ++k)
            for (int i : {4, 5, 8}) picks.push_back(level.regular[k].points[i]);
        for (uint32_t k = 0; picks.size() < 4 && k < level.limit.count(); ++k) picks.push_back(level.limit.vertex[k]);
        std::sort(picks.begin(), picks.end());
        picks.erase(std::unique(picks.begin(), picks.end()), picks.end());
        float s = size * 0.01f;
        for (size_t i = 0; i < picks.size(); ++i) {
            uint32_t v = picks[i];
            switch (i % 3) {
            case 0:  // several adds and subtracts
                out.push_back({l, v, EditOp::Add, {s, 0.5f * s, -0.25f * s}});
                out.push_back({l, v, EditOp::Subtract, {0.125f * s, -s, 0.3f * s}});
                out.push_back({l, v, EditOp::Add, {0.7f * s, 0.1f * s, 0.9f * s}});
                break;
            case 1:  // one set, then an add
                out.push_back(
                    {l, v, EditOp::Set, {asset.positions[0] + s, asset.positions[1] - s, asset.positions[2] + 2 * s}});
                out.push_back({l, v, EditOp::Add, {0.5f * s, 0.5f * s, 0.5f * s}});
                break;
            default: out.push_back({l, v, EditOp::Subtract, {0.3f * s, 0.6f * s, -0.9f * s}});
            }
        }
    }
    return out;
}

}  // namespace lt::test
