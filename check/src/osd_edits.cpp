// The uniform prefix of a mesh with hierarchical edits (osd_edits.h).
#include "osd_edits.h"

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <algorithm>
#include <sstream>

namespace lt {
namespace {

void applyEdit(const InputMesh::VertexEdit& e, OsdPoint& point) {
    for (int k = 0; k < 3; ++k) {
        const double value = double(e.value[k]);
        double& p = point.p[k];
        p = e.op == EditOp::Set ? value : e.op == EditOp::Add ? p + value : p - value;
    }
}

std::string describe(size_t i, const InputMesh::VertexEdit& e) {
    std::ostringstream s;
    s << "edit " << i << " (face " << e.face << ", path [";
    for (size_t k = 0; k < e.path.size(); ++k) s << (k ? " " : "") << int(e.path[k]);
    s << "], vertex " << int(e.vertex) << ")";
    return s.str();
}

// The level-l vertex edit `e` names in `uniform` (l = e.path.size()); `e` is in
// range (checkEdits).
OsdIndex editedVertex(const Far::TopologyRefiner& uniform, const InputMesh::VertexEdit& e) {
    OsdIndex f = OsdIndex(e.face);
    for (size_t l = 0; l < e.path.size(); ++l) f = uniform.GetLevel(int(l)).GetFaceChildFaces(f)[e.path[l]];
    return uniform.GetLevel(int(e.path.size())).GetFaceVertices(f)[e.vertex];
}

// Level `level` as a mesh of its own: faces, the sharpness its edges and vertices
// hold (Far's boundary and non-manifold edges are infinitely sharp already), holes,
// the source's options. Positions from `points`.
InputMesh levelMesh(const Far::TopologyLevel& level, const std::vector<OsdPoint>& points, const InputMesh& source) {
    InputMesh m;
    m.boundary = source.boundary;
    m.creaseMethod = source.creaseMethod;
    m.positions.reserve(3 * points.size());
    for (const OsdPoint& p : points)
        for (int k = 0; k < 3; ++k) m.positions.push_back(float(p.p[k]));
    m.faces.reserve(3 * size_t(level.GetNumFaces()));
    for (OsdIndex f = 0; f < level.GetNumFaces(); ++f) {
        for (OsdIndex v : level.GetFaceVertices(f)) m.faces.push_back(uint32_t(v));
        if (level.IsFaceHole(f)) m.holes.push_back(uint32_t(f));
    }
    for (OsdIndex e = 0; e < level.GetNumEdges(); ++e) {
        const float s = level.GetEdgeSharpness(e);
        if (!(s > 0.0f)) continue;
        const auto ev = level.GetEdgeVertices(e);
        m.creases.push_back({uint32_t(ev[0]), uint32_t(ev[1]), s});
    }
    for (OsdIndex v = 0; v < level.GetNumVertices(); ++v) {
        const float s = level.GetVertexSharpness(v);
        if (s > 0.0f) m.corners.push_back({uint32_t(v), s});
    }
    return m;
}

}  // namespace

Status checkEdits(const InputMesh& mesh) {
    for (size_t i = 0; i < mesh.edits.size(); ++i) {
        const InputMesh::VertexEdit& e = mesh.edits[i];
        const char* why = e.face >= mesh.faceCount() ? "face out of range"
                          : e.vertex > 2             ? "vertex out of range (0..2)"
                          : std::any_of(e.path.begin(), e.path.end(), [](uint8_t c) { return c > 3; })
                              ? "child out of range (0..3)"
                              : nullptr;
        if (why) return Status::error(Status::BadInput, "oracle: " + describe(i, e) + ": " + why);
    }
    return Status::ok();
}

std::vector<OsdPoint> controlPoints(const InputMesh& mesh) {
    std::vector<OsdPoint> points(mesh.vertexCount());
    for (size_t v = 0; v < points.size(); ++v)
        for (int k = 0; k < 3; ++k) points[v].p[k] = mesh.positions[3 * v + size_t(k)];
    return points;
}

std::vector<OsdPoint> editedControlPoints(const InputMesh& mesh) {
    std::vector<OsdPoint> points = controlPoints(mesh);
    for (const auto& e : mesh.edits)
        if (e.path.empty()) applyEdit(e, points[mesh.faces[3 * size_t(e.face) + e.vertex]]);
    return points;
}

Status buildEditedPrefix(const InputMesh& mesh, EditedPrefix& out) {
    out = EditedPrefix{};
    if (Status st = checkEdits(mesh); !st) return st;
    out.depth = int(mesh.editDepth());
    const uint64_t faces = uint64_t(mesh.faceCount()) << (2 * std::min(out.depth, 16));
    if (out.depth > 16 || faces > kMaxEditedPrefixFaces) {
        std::ostringstream s;
        s << "the OpenSubdiv reference for hierarchical edits down to level " << out.depth << " would refine all "
          << mesh.faceCount() << " faces to level " << out.depth << " (" << faces << " faces, more than "
          << kMaxEditedPrefixFaces << ")";
        return Status::error(Status::Unsupported, s.str());
    }
    // The mesh's own refiner (no refinement: its level 0 only), copied to refine uniformly.
    if (Status st = oracleRefiner(mesh, "oracle", out.base); !st) return st;
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    out.uniform.reset(Factory::Create(*out.base));
    Far::TopologyRefiner::UniformOptions uniform(out.depth);
    uniform.fullTopologyInLastLevel = true;  // level K's edges: its crease sharpness
    out.uniform->RefineUniform(uniform);

    // Each edit's vertex, by level.
    std::vector<std::vector<std::pair<OsdIndex, size_t>>> byLevel(size_t(out.depth) + 1);
    for (size_t i = 0; i < mesh.edits.size(); ++i)
        byLevel[mesh.edits[i].path.size()].push_back({editedVertex(*out.uniform, mesh.edits[i]), i});
    // Level by level: interpolate from the edited level above, then this level's edits.
    std::vector<OsdPoint> points = controlPoints(mesh), next;
    Far::PrimvarRefinerReal<double> primvar(*out.uniform);
    for (int l = 0; l <= out.depth; ++l) {
        if (l > 0) {
            next.assign(size_t(out.uniform->GetLevel(l).GetNumVertices()), OsdPoint{});
            const OsdPoint* src = points.data();
            OsdPoint* dst = next.data();
            primvar.Interpolate(l, src, dst);
            points.swap(next);
        }
        for (const auto& [v, i] : byLevel[size_t(l)]) applyEdit(mesh.edits[i], points[size_t(v)]);
    }
    out.last = levelMesh(out.uniform->GetLevel(out.depth), points, mesh);
    out.points = std::move(points);
    return Status::ok();
}

OsdIndex locateSubface(const Far::TopologyRefiner& uniform, int depth, int face, double& u, double& v) {
    OsdIndex f = OsdIndex(face);
    for (int l = 0; l < depth; ++l) {
        int child = 0;
        if (u >= 0.5)
            child = 1, u = 2 * u - 1, v = 2 * v;
        else if (v >= 0.5)
            child = 2, u = 2 * u, v = 2 * v - 1;
        else if (u + v > 0.5)
            child = 3, u = 1 - 2 * u, v = 1 - 2 * v;
        else
            u = 2 * u, v = 2 * v;
        f = uniform.GetLevel(l).GetFaceChildFaces(f)[child];
    }
    return f;
}

}  // namespace lt
