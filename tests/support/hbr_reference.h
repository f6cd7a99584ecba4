// Test oracle for hierarchical edits: OpenSubdiv's Hbr (header-only,
// deprecated, installed with libosd-dev 3.5 under opensubdiv/hbr/), the last
// OpenSubdiv code that implements Loop vertex edits. Far dropped them in 3.0.
//
//   lt::test::HbrReference hbr;
//   lt::test::HbrVertexEdit e;                 // vertex 2 of sub-triangle (7; 1, 3)
//   e.face = 7; e.children = {1, 3}; e.vertex = 2;
//   e.op = lt::test::HbrEditOp::Add; e.value[1] = 0.1f;
//   lt::Status st = hbr.build(mesh, {e}, 3);  // uniform refinement to level 3
//   uint32_t v = hbr.vertex(7, {1, 3}, 2);    // that vertex at level 2
//   const double* p = hbr.position(2, v);     // after the edit
//
// Paths. A sub-triangle of level k is (base face; c_1 .. c_k) in Loop's child
// order, the same in Hbr and in Far (tests/check/test_hbr_oracle.cpp checks it):
// child i (0..2) keeps the parent's corner i in position i, as (v0, e0, e2),
// (e0, v1, e1), (e2, e1, v2); child 3 is the middle triangle (e1, e2, e0), where
// e_i is the edge point of parent edge i (corner i -> corner i+1). A vertex edit
// names corner `vertex` (0..2) of such a sub-triangle and applies at level k:
// after level k's points are computed, before level k+1's (k = 0 edits the
// control point itself).
//
// Per level, the oracle numbers the level's vertices in order of first use by the
// level's sub-triangles, taken in path order (subFace()); faceVertices holds each
// sub-triangle's three vertices in that numbering.
//
// Limits. Hbr has no limit evaluation (HbrSubdivision::HasLimit only says whether
// a limit exists). The oracle applies Loop's exact limit masks to the final level's
// (edited) points itself: smooth and dart vertices the smooth mask over the ring,
// crease vertices (two infinitely sharp or boundary edges) 1/6 2/3 1/6, corners
// (infinitely sharp vertex or more than two sharp edges) the point itself. A vertex
// touched by a semi-sharp edge or with semi-sharp vertex sharpness left at the
// final level has no exact mask there: hasLimit() is false for it.
//
// Supported: triangles, manifold, creases and corners (Hbr's uniform creasing,
// CreaseMethod::Normal), holes, boundary EdgeOnly or EdgeAndCorner. Chaikin
// creasing (Hbr is known to differ from Far), BoundaryInterpolation::None and
// non-manifold meshes are refused (Unsupported).
#pragma once

#include "looptess/tools/baker.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace lt::test {

enum class HbrEditOp : uint8_t { Set, Add, Subtract };

struct HbrVertexEdit {
    uint32_t face = 0;              // base face (InputMesh::faces order)
    std::vector<uint8_t> children;  // c_1 .. c_k, each 0..3; k is the edit's level
    uint8_t vertex = 0;             // corner 0..2 of the sub-triangle
    HbrEditOp op = HbrEditOp::Add;
    float value[3] = {0, 0, 0};  // Hbr stores edit values as float
    int level() const { return int(children.size()); }
};

struct HbrLevel {
    std::vector<double> positions;       // 3 per vertex, after this level's edits
    std::vector<uint32_t> faceVertices;  // 3 per sub-triangle, in path order (subFace)
    uint32_t vertexCount() const { return uint32_t(positions.size() / 3); }
    uint32_t faceCount() const { return uint32_t(faceVertices.size() / 3); }
};

// Shorthand: corner `vertex` of sub-triangle (face; children), edited by `op`.
inline HbrVertexEdit hbrEdit(uint32_t face, std::vector<uint8_t> children, uint8_t vertex, HbrEditOp op, float x,
                             float y, float z) {
    HbrVertexEdit e;
    e.face = face;
    e.children = std::move(children);
    e.vertex = vertex;
    e.op = op;
    e.value[0] = x, e.value[1] = y, e.value[2] = z;
    return e;
}

class HbrReference {
public:
    HbrReference();
    ~HbrReference();
    HbrReference(const HbrReference&) = delete;
    HbrReference& operator=(const HbrReference&) = delete;

    // Builds an Hbr Loop mesh of `mesh` (which must have passed checkInput) with
    // `edits`, refines it uniformly to level `levels` (1..6) and keeps every
    // level's points and the final level's limit points. BadInput names the first
    // bad edit (face out of range, child > 3, vertex > 2, level above `levels`);
    // Unsupported as listed above. Edits naming the same vertex (through one path
    // or several) all apply; Hbr leaves their order unspecified, so only mix adds
    // and subtracts on one vertex.
    Status build(const InputMesh& mesh, const std::vector<HbrVertexEdit>& edits, int levels);

    int levels() const { return int(levels_.size()) - 1; }
    const HbrLevel& level(int l) const { return levels_[size_t(l)]; }
    const double* position(int l, uint32_t v) const { return &levels_[size_t(l)].positions[3 * size_t(v)]; }

    // Index of sub-triangle (face; children[0 .. k)) among level k's sub-triangles:
    // face * 4^k + sum_i children[i] * 4^(k-1-i).
    static uint64_t subFace(uint32_t face, const uint8_t* children, int k);
    // Vertex `corner` of sub-triangle (face; children) at level children.size(),
    // in that level's numbering. Arguments must be in range.
    uint32_t vertex(uint32_t face, const std::vector<uint8_t>& children, int corner) const;

    // Limit point of vertex v of the final level; false (and no point) where the
    // oracle has no exact mask (see above).
    bool hasLimit(uint32_t v) const { return limitValid_[v] != 0; }
    const double* limit(uint32_t v) const { return &limit_[3 * size_t(v)]; }

private:
    std::vector<HbrLevel> levels_;
    std::vector<double> limit_;  // 3 per final-level vertex
    std::vector<uint8_t> limitValid_;
};

}  // namespace lt::test
