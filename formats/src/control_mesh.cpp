// formats/src/control_mesh.cpp -- rules 10, 11 and 45: a surface's control mesh from
// its cage primitives and their controlVertex maps (layout.h, rebuildControlMesh).
//
//   cage primitive 0: vertices 0..n0-1 --controlVertex--> control vertices
//   cage primitive 1: vertices 0..n1-1 --controlVertex--> (the same numbering)
//   base faces: primitive 0's triangles, then primitive 1's, ..., each corner
//   controlVertex[indices[c]]; a triangle with two corners at one control vertex is
//   no base face (a line or a point: a glTF viewer draws nothing for it either).
#include "layout.h"

#include <algorithm>
#include <cstring>

namespace lt::fmt {

Status rebuildControlMesh(std::vector<CagePrimitive>& prims, const std::string& file, Asset& asset,
                          std::vector<uint32_t>& primitiveFaces) {
    auto str = [](uint64_t v) { return std::to_string(v); };
    uint64_t n = 0, vertices = 0;
    bool anyUVs = false, anyUV1s = false, anyColors = false;
    for (CagePrimitive& p : prims) {
        const uint64_t vcount = p.positions.size() / 3;
        if (p.cv.empty()) {
            p.cv.resize(size_t(vcount));
            for (size_t v = 0; v < p.cv.size(); ++v) p.cv[v] = uint32_t(v);
        }
        if (!p.cv.empty()) n = std::max(n, *std::max_element(p.cv.begin(), p.cv.end()) + uint64_t(1));
        vertices += vcount;
        anyUVs = anyUVs || !p.uvs.empty();
        anyUV1s = anyUV1s || !p.uvs1.empty();
        anyColors = anyColors || !p.colors.empty();
    }
    // Before allocating per control vertex: more control vertices than primitive
    // vertices leaves some without a copy.
    if (n > vertices)
        return ruleError(file, prims.back().cvPath, kRuleControlVertexCover,
                         "maximum " + str(n - 1) + " leaves control vertices without a primitive vertex");
    std::vector<int64_t> first(size_t(n), -1);  // (primitive << 32 | vertex) of each control vertex's first copy
    auto position = [&](int64_t at) { return &prims[size_t(at >> 32)].positions[3 * size_t(at & 0xFFFFFFFF)]; };
    for (size_t k = 0; k < prims.size(); ++k) {
        const CagePrimitive& p = prims[k];
        for (size_t v = 0; v < p.cv.size(); ++v) {
            const uint32_t c = p.cv[v];
            const int64_t at = int64_t(k) << 32 | int64_t(v);
            if (first[c] < 0) {
                first[c] = at;
            } else if (std::memcmp(position(first[c]), &p.positions[3 * v], 12) != 0) {
                const CagePrimitive& q = prims[size_t(first[c] >> 32)];
                return ruleError(file, p.path + ".attributes.POSITION", kRuleControlVertexPositions,
                                 "vertex " + str(v) + " of control vertex " + str(c) + " differs from vertex " +
                                     str(uint64_t(first[c] & 0xFFFFFFFF)) + " of " + q.path);
            }
        }
    }
    asset.positions.resize(size_t(3 * n));
    for (size_t c = 0; c < n; ++c) {
        if (first[c] < 0)
            return ruleError(file, prims.back().cvPath, kRuleControlVertexCover,
                             "no primitive vertex maps to control vertex " + str(c));
        std::memcpy(&asset.positions[3 * c], position(first[c]), 12);
    }
    asset.faces.clear();
    asset.faceUVs.clear();
    asset.faceUV1s.clear();
    asset.faceColors.clear();
    primitiveFaces.assign(1, 0);
    for (const CagePrimitive& p : prims) {
        for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
            const uint32_t* i = &p.indices[t];
            const uint32_t a = p.cv[i[0]], b = p.cv[i[1]], c = p.cv[i[2]];
            if (a == b || b == c || c == a) continue;
            asset.faces.insert(asset.faces.end(), {a, b, c});
            for (int k = 0; k < 3; ++k) {
                const size_t v = i[k];
                for (int j = 0; anyUVs && j < 2; ++j) asset.faceUVs.push_back(p.uvs.empty() ? 0.0f : p.uvs[2 * v + j]);
                for (int j = 0; anyUV1s && j < 2; ++j)
                    asset.faceUV1s.push_back(p.uvs1.empty() ? 0.0f : p.uvs1[2 * v + j]);
                for (int j = 0; anyColors && j < 4; ++j)
                    asset.faceColors.push_back(p.colors.empty() ? 1.0f : p.colors[4 * v + j]);
            }
        }
        primitiveFaces.push_back(uint32_t(asset.faces.size() / 3));
    }
    return Status::ok();
}

}  // namespace lt::fmt
