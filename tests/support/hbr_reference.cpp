// Hbr oracle for hierarchical edits (see hbr_reference.h).
//
// How Hbr is driven (OpenSubdiv's old regression code, regression/common/hbr_utils.h
// at v3_5_0, does the same steps): vertices, then faces, then the tags (creases,
// corners, holes, boundary method, hierarchical edits) are given to an HbrMesh
// before HbrMesh::Finish(), which sorts the edits by path and links each base face
// to its own. HbrFace::Refine() makes a face's four children; an edit is handed
// down the path with the children (transferEditsToChild) and marks its vertex
// when the sub-triangle at its depth is created; HbrVertex::GuaranteeNeighbors()
// applies the marked edits to the vertex's data. Hbr is lazy: GuaranteeNeighbors
// runs when something first needs the vertex's neighbourhood (its own vertex point,
// a neighbour's vertex point, an edge point at one of its edges), so reading level
// k's points right after making them would miss its edits. This oracle calls
// GuaranteeNeighbors on every vertex of level k (which refines nothing new: level
// k-1 is complete) before it reads level k and before it refines it, so every edit
// of level k is in place before level k+1 reads it, whatever order Hbr would have
// got there in. (Letting Hbr refine in its own lazy order and reading afterwards
// gave the same bits on every case of tests/check/test_hbr_oracle.cpp.)
#include "hbr_reference.h"

#include <opensubdiv/hbr/mesh.h>
#include <opensubdiv/hbr/loop.h>
#include <opensubdiv/hbr/vertexEdit.h>

#include <cmath>
#include <memory>
#include <string>

namespace lt::test {
namespace {

namespace Osd = OpenSubdiv;

// Hbr's vertex data (its <class T>): a point, in double. Hbr hands float weights.
struct HbrPoint {
    double p[3] = {0, 0, 0};

    HbrPoint() = default;
    explicit HbrPoint(int) {}  // HbrMesh::NewVertex() makes T(vertex id)
    void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
    void AddWithWeight(const HbrPoint& src, float weight, void* = nullptr) {
        for (int k = 0; k < 3; ++k) p[k] += double(weight) * src.p[k];
    }
    void AddVaryingWithWeight(const HbrPoint&, float, void* = nullptr) {}
    void ApplyVertexEdit(const Osd::HbrVertexEdit<HbrPoint>& edit) {
        const float* v = edit.GetEdit();
        for (int k = 0; k < 3; ++k) {
            switch (edit.GetOperation()) {
            case Osd::HbrHierarchicalEdit<HbrPoint>::Set: p[k] = double(v[k]); break;
            case Osd::HbrHierarchicalEdit<HbrPoint>::Add: p[k] += double(v[k]); break;
            case Osd::HbrHierarchicalEdit<HbrPoint>::Subtract: p[k] -= double(v[k]); break;
            }
        }
    }
    void ApplyMovingVertexEdit(const Osd::HbrMovingVertexEdit<HbrPoint>&) {}
};

using Mesh = Osd::HbrMesh<HbrPoint>;
using Face = Osd::HbrFace<HbrPoint>;
using Vertex = Osd::HbrVertex<HbrPoint>;
using Halfedge = Osd::HbrHalfedge<HbrPoint>;
using Loop = Osd::HbrLoopSubdivision<HbrPoint>;

constexpr float kInfSharp = float(Halfedge::k_InfinitelySharp);  // 10, as Sdc's

Status bad(Status::Code code, const std::string& what) { return Status::error(code, "hbr oracle: " + what); }

std::string describe(const HbrVertexEdit& e) {
    std::string s = "edit (face " + std::to_string(e.face) + ";";
    for (uint8_t c : e.children) s += " " + std::to_string(int(c));
    return s + "; vertex " + std::to_string(int(e.vertex)) + ")";
}

// Loop's exact limit point of `v` from its (complete) neighbourhood, or false.
bool limitPoint(Vertex* v, double out[3]) {
    const float vs = v->GetSharpness();
    if (vs > 0.0f && vs < kInfSharp) return false;
    std::vector<Halfedge*> edges;
    v->GetSurroundingEdges(std::back_inserter(edges));
    std::vector<const HbrPoint*> ring, sharp;
    for (Halfedge* e : edges) {
        const float es = e->GetSharpness();
        if (es > 0.0f && es < kInfSharp) return false;
        Vertex* other = e->GetOrgVertex() == v ? e->GetDestVertex() : e->GetOrgVertex();
        ring.push_back(&other->GetData());
        if (es >= kInfSharp || e->IsBoundary()) sharp.push_back(&other->GetData());
    }
    const double* c = v->GetData().p;
    if (vs >= kInfSharp || sharp.size() > 2) {  // corner
        for (int k = 0; k < 3; ++k) out[k] = c[k];
    } else if (sharp.size() == 2) {  // crease or boundary: 1/6 2/3 1/6
        for (int k = 0; k < 3; ++k) out[k] = (sharp[0]->p[k] + 4.0 * c[k] + sharp[1]->p[k]) / 6.0;
    } else {  // smooth or dart: Loop's limit mask
        if (v->OnBoundary() || ring.size() < 3) return false;
        const double n = double(ring.size());
        const double a = 0.375 + 0.25 * std::cos(2.0 * M_PI / n);
        const double beta = (0.625 - a * a) / n;
        const double self = 3.0 / (8.0 * beta);
        for (int k = 0; k < 3; ++k) {
            double sum = self * c[k];
            for (const HbrPoint* r : ring) sum += r->p[k];
            out[k] = sum / (n + self);
        }
    }
    return true;
}

Status checkEdits(const InputMesh& mesh, const std::vector<HbrVertexEdit>& edits, int levels) {
    for (const HbrVertexEdit& e : edits) {
        if (e.face >= mesh.faceCount())
            return bad(Status::BadInput,
                       describe(e) + ": face out of range (" + std::to_string(mesh.faceCount()) + " faces)");
        for (uint8_t c : e.children)
            if (c > 3) return bad(Status::BadInput, describe(e) + ": child " + std::to_string(int(c)) + " > 3");
        if (e.vertex > 2)
            return bad(Status::BadInput, describe(e) + ": vertex " + std::to_string(int(e.vertex)) + " > 2");
        if (e.level() > levels)
            return bad(Status::BadInput, describe(e) + ": level " + std::to_string(e.level()) +
                                             " is above the refinement level " + std::to_string(levels));
        for (float x : e.value)
            if (!std::isfinite(x)) return bad(Status::BadInput, describe(e) + ": value is not finite");
    }
    return Status::ok();
}

}  // namespace

HbrReference::HbrReference() = default;
HbrReference::~HbrReference() = default;

uint64_t HbrReference::subFace(uint32_t face, const uint8_t* children, int k) {
    uint64_t index = face;
    for (int i = 0; i < k; ++i) index = index * 4 + children[i];
    return index;
}

uint32_t HbrReference::vertex(uint32_t face, const std::vector<uint8_t>& children, int corner) const {
    const int k = int(children.size());
    return levels_[size_t(k)].faceVertices[3 * subFace(face, children.data(), k) + size_t(corner)];
}

Status HbrReference::build(const InputMesh& input, const std::vector<HbrVertexEdit>& edits, int levels) {
    levels_.clear();
    limit_.clear();
    limitValid_.clear();
    if (levels < 1 || levels > 6) return bad(Status::Usage, "levels " + std::to_string(levels) + " not in 1..6");
    if (input.faces.size() % 3 != 0 || input.faces.empty()) return bad(Status::BadInput, "no triangle faces");
    if (input.creaseMethod == CreaseMethod::Chaikin)
        return bad(Status::Unsupported, "Chaikin creasing (Hbr's differs from Far's)");
    if (input.boundary == BoundaryInterpolation::None) return bad(Status::Unsupported, "boundary interpolation None");
    if (Status st = checkEdits(input, edits, levels); !st) return st;

    Loop scheme;
    scheme.SetCreaseSubdivisionMethod(Osd::HbrSubdivision<HbrPoint>::k_CreaseNormal);
    auto mesh = std::make_unique<Mesh>(&scheme);  // destroyed before `scheme`

    const uint32_t nv = input.vertexCount();
    for (uint32_t i = 0; i < nv; ++i) {
        HbrPoint p;
        for (int k = 0; k < 3; ++k) p.p[k] = double(input.positions[3 * size_t(i) + size_t(k)]);
        mesh->NewVertex(int(i), p);
    }
    for (uint32_t f = 0; f < input.faceCount(); ++f) {
        int fv[3];
        for (int j = 0; j < 3; ++j) fv[j] = int(input.faces[3 * size_t(f) + size_t(j)]);
        for (int j = 0; j < 3; ++j) {
            Vertex* org = mesh->GetVertex(fv[j]);
            Vertex* dst = mesh->GetVertex(fv[(j + 1) % 3]);
            if (!org || !dst || org == dst)
                return bad(Status::BadInput, "face " + std::to_string(f) + " is degenerate");
            Halfedge* opposite = dst->GetEdge(org);
            if (org->GetEdge(dst) || (opposite && opposite->GetOpposite()))
                return bad(Status::Unsupported, "face " + std::to_string(f) + ": non-manifold or flipped edge");
        }
        if (!mesh->NewFace(3, fv, int(f))) return bad(Status::BadInput, "face " + std::to_string(f) + " rejected");
    }
    mesh->SetInterpolateBoundaryMethod(input.boundary == BoundaryInterpolation::EdgeAndCorner
                                           ? Mesh::k_InterpolateBoundaryEdgeAndCorner
                                           : Mesh::k_InterpolateBoundaryEdgeOnly);
    for (const InputMesh::Crease& c : input.creases) {
        Vertex* a = mesh->GetVertex(int(c.a));
        Vertex* b = mesh->GetVertex(int(c.b));
        Halfedge* e = a && b ? a->GetEdge(b) : nullptr;
        if (!e && a && b) e = b->GetEdge(a);
        if (!e)
            return bad(Status::BadInput, "crease " + std::to_string(c.a) + "-" + std::to_string(c.b) + " is no edge");
        e->SetSharpness(std::max(0.0f, c.sharpness));  // sets both halfedges
    }
    for (const InputMesh::Corner& c : input.corners) {
        Vertex* v = mesh->GetVertex(int(c.vertex));
        if (!v) return bad(Status::BadInput, "corner " + std::to_string(c.vertex) + " is no vertex");
        v->SetSharpness(std::max(0.0f, c.sharpness));
    }
    for (uint32_t h : input.holes) {
        Face* f = mesh->GetFace(int(h));
        if (!f) return bad(Status::BadInput, "hole " + std::to_string(h) + " is no face");
        f->SetHole();
    }
    for (const HbrVertexEdit& e : edits) {
        std::vector<int> path(e.children.begin(), e.children.end());
        float value[3] = {e.value[0], e.value[1], e.value[2]};
        auto op = e.op == HbrEditOp::Set   ? Osd::HbrHierarchicalEdit<HbrPoint>::Set
                  : e.op == HbrEditOp::Add ? Osd::HbrHierarchicalEdit<HbrPoint>::Add
                                           : Osd::HbrHierarchicalEdit<HbrPoint>::Subtract;
        // Variable index 0, width 3, "P": the edit is a position edit. The mesh owns it.
        mesh->AddHierarchicalEdit(new Osd::HbrVertexEdit<HbrPoint>(int(e.face), int(path.size()), path.data(),
                                                                   int(e.vertex), 0, 3, true, op, value));
    }
    mesh->Finish();
    if (mesh->GetNumVertices() != int(nv))  // Finish splits non-manifold vertices
        return bad(Status::Unsupported, "non-manifold vertex (Hbr split it)");

    std::vector<Face*> faces;
    for (uint32_t f = 0; f < input.faceCount(); ++f) faces.push_back(mesh->GetFace(int(f)));
    std::vector<int32_t> number;    // Hbr vertex id -> this level's index, -1
    std::vector<Vertex*> vertices;  // this level's vertices in order
    for (int l = 0;; ++l) {
        // Apply level l's edits (see the file comment), then read the level.
        for (Face* f : faces)
            for (int j = 0; j < 3; ++j) f->GetVertex(j)->GuaranteeNeighbors();
        HbrLevel out;
        number.assign(size_t(mesh->GetNumVertices()) + 1, -1);
        vertices.clear();
        out.faceVertices.reserve(3 * faces.size());
        for (Face* f : faces)
            for (int j = 0; j < 3; ++j) {
                Vertex* v = f->GetVertex(j);
                const size_t id = size_t(v->GetID());
                if (id >= number.size()) number.resize(id + 1, -1);
                if (number[id] < 0) {
                    number[id] = int32_t(vertices.size());
                    vertices.push_back(v);
                    out.positions.insert(out.positions.end(), v->GetData().p, v->GetData().p + 3);
                }
                out.faceVertices.push_back(uint32_t(number[id]));
            }
        levels_.push_back(std::move(out));
        if (l == levels) break;
        std::vector<Face*> children;
        children.reserve(4 * faces.size());
        for (Face* f : faces) {
            f->Refine();
            for (int i = 0; i < 4; ++i) {
                Face* c = f->GetChild(i);
                if (!c) return bad(Status::Internal, "Hbr made no child " + std::to_string(i));
                children.push_back(c);
            }
        }
        faces.swap(children);
    }
    limit_.assign(3 * vertices.size(), 0.0);
    limitValid_.assign(vertices.size(), 0);
    for (size_t i = 0; i < vertices.size(); ++i) limitValid_[i] = limitPoint(vertices[i], &limit_[3 * i]) ? 1 : 0;
    return Status::ok();
}

}  // namespace lt::test
