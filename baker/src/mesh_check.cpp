// mesh_check.cpp -- lt::checkInput: what subdivision cannot use.
//
// Every check is a scan or a sort, O(n log n) in the number of faces (and linear in
// the edits). Faces are named by their 0-based triangle index, vertices by their
// 0-based index.
#include "looptess/tools/baker.h"
#include "mesh_clean.h"
#include "text.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

namespace lt {
namespace {

// A face's use of an undirected edge lo < hi; `forward` when it runs lo -> hi.
struct EdgeUse {
    uint64_t key;
    uint32_t face;
    bool forward;
};

uint64_t edgeKey(uint32_t a, uint32_t b) { return a < b ? (uint64_t(a) << 32) | b : (uint64_t(b) << 32) | a; }

class Checker {
public:
    Checker(const InputMesh& mesh, const std::string& name) : m_(mesh), name_(name) {}

    Status run(std::vector<std::string>& warnings);

private:
    Status bad(const std::string& what) const { return Status::error(Status::BadInput, name_ + ": " + what); }
    std::string face(size_t f) const { return "face " + std::to_string(f); }

    Status sizes() const;
    Status positions() const;
    Status faces() const;
    void zeroArea(std::vector<std::string>& warnings) const;
    bool sameOrientation(size_t f, size_t g) const;
    Status repeated() const;
    Status orientation() const;
    Status sharpness(const std::string& what, float s) const;
    Status vertex(const std::string& what, uint32_t v) const;
    Status creases() const;
    Status corners() const;
    Status holes() const;
    Status edits() const;

    const InputMesh& m_;
    const std::string& name_;
    std::vector<EdgeUse> edges_;  // every face's 3 edges, sorted by (key, face)
};

Status Checker::sizes() const {
    if (m_.positions.size() % 3 != 0) return bad("position count is not a multiple of 3");
    if (m_.faces.size() % 3 != 0) return bad("face index count is not a multiple of 3");
    if (m_.faces.empty()) return bad("mesh has no faces");
    if (!m_.faceUVs.empty() && m_.faceUVs.size() != 2 * m_.faces.size())
        return bad("texture coordinate count does not match the face count");
    return Status::ok();
}

Status Checker::positions() const {
    for (size_t i = 0; i < m_.positions.size(); ++i)
        if (!std::isfinite(m_.positions[i]))
            return bad("vertex " + std::to_string(i / 3) + " has a non-finite position (" +
                       formatFloat(m_.positions[i]) + ")");
    return Status::ok();
}

Status Checker::faces() const {
    uint32_t n = m_.vertexCount();
    for (size_t f = 0; f < m_.faceCount(); ++f) {
        const uint32_t* v = &m_.faces[3 * f];
        for (int k = 0; k < 3; ++k)
            if (v[k] >= n)
                return bad(face(f) + " references vertex " + std::to_string(v[k]) + ", out of range (mesh has " +
                           std::to_string(n) + " vertices)");
        if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0])
            return bad(face(f) + " is degenerate (vertices " + std::to_string(v[0]) + ", " + std::to_string(v[1]) +
                       ", " + std::to_string(v[2]) + " repeat an index)");
    }
    return Status::ok();
}

// Zero area relative to the longest edge (collinear or coincident corners).
void Checker::zeroArea(std::vector<std::string>& warnings) const {
    size_t count = 0, first = 0;
    for (size_t f = 0; f < m_.faceCount(); ++f) {
        const float* p[3];
        for (int k = 0; k < 3; ++k) p[k] = &m_.positions[3 * size_t(m_.faces[3 * f + k])];
        if (zeroAreaTriangle(p[0], p[1], p[2]) && count++ == 0) first = f;
    }
    if (count != 0)
        warnings.push_back(name_ + ": " + std::to_string(count) + " faces have zero area (first: " + face(first) + ")");
}

// Whether faces f and g (same vertex set) list their vertices in the same cyclic order.
bool Checker::sameOrientation(size_t f, size_t g) const {
    const uint32_t* a = &m_.faces[3 * f];
    const uint32_t* b = &m_.faces[3 * g];
    int k = a[0] == b[0] ? 0 : a[0] == b[1] ? 1 : 2;
    return a[1] == b[(k + 1) % 3];
}

Status Checker::repeated() const {
    std::vector<std::array<uint32_t, 4>> keys(m_.faceCount());  // sorted vertices, face
    for (size_t f = 0; f < keys.size(); ++f) {
        std::array<uint32_t, 3> v = {m_.faces[3 * f], m_.faces[3 * f + 1], m_.faces[3 * f + 2]};
        std::sort(v.begin(), v.end());
        keys[f] = {v[0], v[1], v[2], uint32_t(f)};
    }
    std::sort(keys.begin(), keys.end());
    for (size_t i = 1; i < keys.size(); ++i) {
        const auto& a = keys[i - 1];
        const auto& b = keys[i];
        // The same triangle reversed is a two-sided sheet (OpenSubdiv's
        // loop_val2_interior): legal, its limit surface is flat and doubly covered.
        if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2] && sameOrientation(a[3], b[3]))
            return bad(face(b[3]) + " repeats " + face(a[3]) + " (same vertices " + std::to_string(a[0]) + ", " +
                       std::to_string(a[1]) + ", " + std::to_string(a[2]) + ", same orientation)");
    }
    return Status::ok();
}

// An edge with exactly two faces must be used once in each direction. Edges with
// more faces are non-manifold, which OpenSubdiv accepts.
Status Checker::orientation() const {
    for (size_t i = 0; i < edges_.size();) {
        size_t j = i;
        while (j < edges_.size() && edges_[j].key == edges_[i].key) ++j;
        const EdgeUse& a = edges_[i];
        if (j - i == 2 && a.forward == edges_[i + 1].forward) {
            uint32_t lo = uint32_t(a.key >> 32), hi = uint32_t(a.key);
            if (!a.forward) std::swap(lo, hi);
            return bad("faces " + std::to_string(a.face) + " and " + std::to_string(edges_[i + 1].face) +
                       " both use edge " + std::to_string(lo) + "->" + std::to_string(hi) +
                       " in the same direction (inconsistent orientation: a flipped face or "
                       "a non-orientable mesh)");
        }
        i = j;
    }
    return Status::ok();
}

Status Checker::sharpness(const std::string& what, float s) const {
    if (std::isnan(s)) return bad(what + " has an invalid sharpness (nan)");
    if (s < 0) return bad(what + " has negative sharpness " + formatFloat(s));
    return Status::ok();
}

Status Checker::vertex(const std::string& what, uint32_t v) const {
    if (v >= m_.vertexCount())
        return bad(what + " names vertex " + std::to_string(v) + ", out of range (mesh has " +
                   std::to_string(m_.vertexCount()) + " vertices)");
    return Status::ok();
}

Status Checker::creases() const {
    for (size_t i = 0; i < m_.creases.size(); ++i) {
        const InputMesh::Crease& c = m_.creases[i];
        std::string what =
            "crease " + std::to_string(i) + " (vertices " + std::to_string(c.a) + "-" + std::to_string(c.b) + ")";
        if (Status st = vertex(what, c.a); !st) return st;
        if (Status st = vertex(what, c.b); !st) return st;
        if (Status st = sharpness(what, c.sharpness); !st) return st;
        uint64_t key = edgeKey(c.a, c.b);
        auto it =
            std::lower_bound(edges_.begin(), edges_.end(), key, [](const EdgeUse& e, uint64_t k) { return e.key < k; });
        if (c.a == c.b || it == edges_.end() || it->key != key) return bad(what + " is not an edge of the mesh");
    }
    return Status::ok();
}

Status Checker::corners() const {
    for (size_t i = 0; i < m_.corners.size(); ++i) {
        std::string what = "corner " + std::to_string(i);
        if (Status st = vertex(what, m_.corners[i].vertex); !st) return st;
        if (Status st = sharpness(what, m_.corners[i].sharpness); !st) return st;
    }
    return Status::ok();
}

Status Checker::holes() const {
    for (size_t i = 0; i < m_.holes.size(); ++i)
        if (m_.holes[i] >= m_.faceCount())
            return bad("hole " + std::to_string(i) + " names " + face(m_.holes[i]) + ", out of range (mesh has " +
                       std::to_string(m_.faceCount()) + " faces)");
    return Status::ok();
}

// Hierarchical edits, each named as its input wrote it: "vertex edit 3 (face 7 path
// 1 3 vertex 2)". Depth against maxDepth and `set` sharing a vertex are bake's checks.
Status Checker::edits() const {
    std::vector<uint8_t> hole(m_.faceCount(), 0);
    for (uint32_t h : m_.holes) hole[h] = 1;  // holes() ran: every index is in range
    for (size_t i = 0; i < m_.edits.size(); ++i) {
        const InputMesh::VertexEdit& e = m_.edits[i];
        std::string what = "vertex edit " + std::to_string(i) + " (" + face(e.face);
        if (!e.path.empty()) what += " path";
        for (uint8_t c : e.path) what += " " + std::to_string(c);
        what += " vertex " + std::to_string(e.vertex) + ")";
        if (e.face >= m_.faceCount())
            return bad(what + " names " + face(e.face) + ", out of range (mesh has " + std::to_string(m_.faceCount()) +
                       " faces)");
        for (uint8_t c : e.path)
            if (c > 3) return bad(what + " has child " + std::to_string(c) + "; children are 0..3");
        if (e.vertex > 2)
            return bad(what + " has vertex " + std::to_string(e.vertex) + "; triangles have corners 0..2");
        if (uint8_t(e.op) > uint8_t(EditOp::Subtract))
            return bad(what + " has an unknown operation " + std::to_string(unsigned(e.op)));
        for (float v : e.value)
            if (!std::isfinite(v)) return bad(what + " has a non-finite value (" + formatFloat(v) + ")");
        if (hole[e.face]) return bad(what + " edits " + face(e.face) + ", which is a hole");
    }
    return Status::ok();
}

Status Checker::run(std::vector<std::string>& warnings) {
    if (Status st = sizes(); !st) return st;
    if (Status st = positions(); !st) return st;
    if (Status st = faces(); !st) return st;
    if (Status st = repeated(); !st) return st;
    edges_.reserve(m_.faces.size());
    for (uint32_t f = 0; f < m_.faceCount(); ++f)
        for (int k = 0; k < 3; ++k) {
            uint32_t a = m_.faces[3 * f + k], b = m_.faces[3 * f + (k + 1) % 3];
            edges_.push_back({edgeKey(a, b), f, a < b});
        }
    std::sort(edges_.begin(), edges_.end(),
              [](const EdgeUse& x, const EdgeUse& y) { return x.key != y.key ? x.key < y.key : x.face < y.face; });
    if (Status st = orientation(); !st) return st;
    if (Status st = creases(); !st) return st;
    if (Status st = corners(); !st) return st;
    if (Status st = holes(); !st) return st;
    if (Status st = edits(); !st) return st;
    zeroArea(warnings);
    return Status::ok();
}

}  // namespace

Status checkInput(const InputMesh& mesh, const std::string& name, std::vector<std::string>& warnings) {
    try {
        return Checker(mesh, name).run(warnings);
    } catch (const std::exception& e) {  // bad_alloc, in practice
        return Status::error(Status::Internal, name + ": " + e.what());
    }
}

Status checkInput(const InputMesh& mesh, const std::string& name) {
    std::vector<std::string> ignored;
    return checkInput(mesh, name, ignored);
}

}  // namespace lt
