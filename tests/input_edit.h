// Shorthand for a hierarchical vertex edit of an InputMesh (baker.h), shared by the
// edit tests.
#pragma once

#include "looptess/baker.h"

#include <cstdint>
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

} // namespace lt::test
