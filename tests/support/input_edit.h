// Shorthand for a hierarchical vertex edit of an InputMesh (baker.h), shared by the
// edit tests.
#pragma once

#include "looptess/tools/baker.h"
#include "looptess/runtime.h"

#include <cstdint>
#include <set>
#include <utility>
#include <vector>

namespace lt::test {

// Corner `vertex` of sub-triangle (face; path), edited by `op` with (x, y, z).
inline InputMesh::VertexEdit inputEdit(uint32_t face, std::vector<uint8_t> path, uint8_t vertex, EditOp op, float x,
                                       float y, float z) {
    InputMesh::VertexEdit e;
    e.face = face;
    e.path = std::move(path);
    e.vertex = vertex;
    e.op = op;
    e.value[0] = x, e.value[1] = y, e.value[2] = z;
    return e;
}

// Base faces within `rings` vertex rings of the faces `edits` name, on a control
// mesh of `faces` (3 indices per triangle).
inline std::set<uint32_t> facesNearEdits(const std::vector<InputMesh::VertexEdit>& edits,
                                         const std::vector<uint32_t>& faces, int rings) {
    std::set<uint32_t> near, vertices;
    for (const auto& e : edits) near.insert(e.face);
    for (int r = 0; r < rings; ++r) {
        for (uint32_t f : near)
            for (int k = 0; k < 3; ++k) vertices.insert(faces[3 * f + k]);
        for (uint32_t f = 0; f < faces.size() / 3; ++f)
            for (int k = 0; k < 3; ++k)
                if (vertices.count(faces[3 * f + k])) near.insert(f);
    }
    return near;
}

// Positions and normals (6 floats per vertex) of a soup's vertices on base faces not
// in `skip`, in emission order.
inline std::vector<float> verticesOutside(const Tessellation& t, const std::set<uint32_t>& skip) {
    std::vector<float> out;
    for (size_t i = 0; i < t.vertexCount(); ++i) {
        if (skip.count(t.face[i])) continue;
        out.insert(out.end(), &t.positions[3 * i], &t.positions[3 * i] + 3);
        out.insert(out.end(), &t.normals[3 * i], &t.normals[3 * i] + 3);
    }
    return out;
}

}  // namespace lt::test
