// usd_mesh.cpp -- a Mesh prim's attributes checked and turned into its cage
// primitive and, for a Loop mesh, its control mesh (usd_data.h, buildMesh).
#include "usd_data.h"

#include "looptess/tools/triangulate.h"

#include <algorithm>
#include <cstring>
#include <unordered_map>

namespace lt::usd {
namespace {

struct Context {
    const MeshData& m;
    const std::string& file;
    Status fail(const std::string& attribute, const std::string& what) const {
        return Status::error(Status::BadInput, file + ": " + m.path + ": " + attribute + ": " + what);
    }
};

// Which value of a primvar face corner (face f, corner c of all, point p) reads,
// after its indices: -1 when the primvar is absent.
struct PrimvarReader {
    const Primvar& pv;
    int mode = -1;  // 0 constant, 1 uniform, 2 vertex/varying, 3 faceVarying

    Status check(const Context& ctx, const std::string& name, size_t faces, size_t points, size_t corners) {
        if (!pv.present) return Status::ok();
        size_t want = 0;
        if (pv.interpolation == "constant")
            mode = 0, want = 1;
        else if (pv.interpolation == "uniform")
            mode = 1, want = faces;
        else if (pv.interpolation == "vertex" || pv.interpolation == "varying")
            mode = 2, want = points;
        else if (pv.interpolation == "faceVarying")
            mode = 3, want = corners;
        else
            return ctx.fail(name, "interpolation \"" + pv.interpolation + "\" is not a UsdGeom interpolation");
        const size_t values = pv.values.size() / size_t(pv.components);
        const size_t have = pv.indexed ? pv.indices.size() : values;
        if (have != want)
            return ctx.fail(pv.indexed ? name + ":indices" : name,
                            std::to_string(have) + " values for " + pv.interpolation + " interpolation, which needs " +
                                std::to_string(want));
        if (pv.indexed)
            for (size_t i = 0; i < pv.indices.size(); ++i)
                if (pv.indices[i] < 0 || size_t(pv.indices[i]) >= values)
                    return ctx.fail(name + ":indices", "[" + std::to_string(i) +
                                                           "] = " + std::to_string(pv.indices[i]) +
                                                           " is out of range (" + std::to_string(values) + " values)");
        return Status::ok();
    }
    const float* at(size_t face, size_t corner, size_t point) const {
        if (mode < 0) return nullptr;
        size_t i = mode == 0 ? 0 : mode == 1 ? face : mode == 2 ? point : corner;
        if (pv.indexed) i = size_t(pv.indices[i]);
        return &pv.values[i * size_t(pv.components)];
    }
};

Status checkTopology(const Context& ctx, const InputOptions& options, size_t& triangles) {
    const MeshData& m = ctx.m;
    if (!m.hasPoints) return ctx.fail("points", "missing (a mesh needs points)");
    if (!m.hasCounts) return ctx.fail("faceVertexCounts", "missing");
    if (!m.hasIndices) return ctx.fail("faceVertexIndices", "missing");
    const size_t points = m.points.size() / 3;
    if (points > options.limits.maxVertices)
        return ctx.fail("points", std::to_string(points) + " points, more than the limit of " +
                                      std::to_string(options.limits.maxVertices) + " (raise it with --max-vertices)");
    size_t corners = 0;
    triangles = 0;
    for (size_t f = 0; f < m.counts.size(); ++f) {
        const int n = m.counts[f];
        if (n < 3)
            return ctx.fail("faceVertexCounts", "[" + std::to_string(f) + "] = " + std::to_string(n) +
                                                    ": a face needs at least 3 vertices");
        if (n > 3 && options.strict)
            return ctx.fail("faceVertexCounts",
                            "[" + std::to_string(f) + "] = " + std::to_string(n) + ": --strict takes triangles only");
        corners += size_t(n);
        triangles += size_t(n) - 2;
    }
    if (corners != m.indices.size())
        return ctx.fail(
            "faceVertexIndices",
            std::to_string(m.indices.size()) + " indices, but faceVertexCounts adds up to " + std::to_string(corners));
    if (triangles > options.limits.maxFaces)
        return ctx.fail("faceVertexCounts", std::to_string(triangles) + " triangles, more than the limit of " +
                                                std::to_string(options.limits.maxFaces) +
                                                " (raise it with --max-faces)");
    for (size_t i = 0; i < m.indices.size(); ++i)
        if (m.indices[i] < 0 || size_t(m.indices[i]) >= points)
            return ctx.fail("faceVertexIndices", "[" + std::to_string(i) + "] = " + std::to_string(m.indices[i]) +
                                                     " is out of range (" + std::to_string(points) + " points)");
    return Status::ok();
}

// Creases, corners and holes into `mesh` (its faces already made; `firstTriangle`
// [f] is polygon f's first triangle).
Status addTags(const Context& ctx, const std::vector<uint32_t>& firstTriangle, InputMesh& mesh) {
    const MeshData& m = ctx.m;
    const size_t points = m.points.size() / 3;
    auto pointIndex = [&](const std::string& name, const std::vector<int>& v, size_t i, Status& st) {
        if (v[i] < 0 || size_t(v[i]) >= points)
            st = ctx.fail(name, "[" + std::to_string(i) + "] = " + std::to_string(v[i]) + " is out of range (" +
                                    std::to_string(points) + " points)");
        return uint32_t(v[i]);
    };
    size_t total = 0, edges = 0;
    for (size_t c = 0; c < m.creaseLengths.size(); ++c) {
        const int n = m.creaseLengths[c];
        if (n < 2)
            return ctx.fail("creaseLengths", "[" + std::to_string(c) + "] = " + std::to_string(n) +
                                                 ": a crease needs at least 2 vertices");
        total += size_t(n);
        edges += size_t(n) - 1;
    }
    if (total != m.creaseIndices.size())
        return ctx.fail("creaseIndices", std::to_string(m.creaseIndices.size()) +
                                             " indices, but creaseLengths adds up to " + std::to_string(total));
    const size_t sharp = m.creaseSharpnesses.size();
    if (sharp != m.creaseLengths.size() && sharp != edges)
        return ctx.fail("creaseSharpnesses", std::to_string(sharp) + " values; needs one a crease (" +
                                                 std::to_string(m.creaseLengths.size()) + ") or one an edge (" +
                                                 std::to_string(edges) + ")");
    const bool perEdge = sharp == edges && sharp != m.creaseLengths.size();
    size_t at = 0, edge = 0;
    Status st = Status::ok();
    for (size_t c = 0; c < m.creaseLengths.size(); ++c) {
        for (int k = 0; k + 1 < m.creaseLengths[c]; ++k, ++edge) {
            const uint32_t a = pointIndex("creaseIndices", m.creaseIndices, at + size_t(k), st);
            const uint32_t b = pointIndex("creaseIndices", m.creaseIndices, at + size_t(k) + 1, st);
            if (!st) return st;
            mesh.creases.push_back({a, b, m.creaseSharpnesses[perEdge ? edge : c]});
        }
        at += size_t(m.creaseLengths[c]);
    }
    if (m.cornerSharpnesses.size() != m.cornerIndices.size())
        return ctx.fail("cornerSharpnesses", std::to_string(m.cornerSharpnesses.size()) + " values for " +
                                                 std::to_string(m.cornerIndices.size()) + " cornerIndices");
    for (size_t i = 0; i < m.cornerIndices.size(); ++i) {
        const uint32_t v = pointIndex("cornerIndices", m.cornerIndices, i, st);
        if (!st) return st;
        mesh.corners.push_back({v, m.cornerSharpnesses[i]});
    }
    for (size_t i = 0; i < m.holeIndices.size(); ++i) {
        const int f = m.holeIndices[i];
        if (f < 0 || size_t(f) >= m.counts.size())
            return ctx.fail("holeIndices", "[" + std::to_string(i) + "] = " + std::to_string(f) + " is out of range (" +
                                               std::to_string(m.counts.size()) + " faces)");
        for (uint32_t t = firstTriangle[size_t(f)]; t < firstTriangle[size_t(f) + 1]; ++t) mesh.holes.push_back(t);
    }
    if (m.boundary == "none")
        mesh.boundary = BoundaryInterpolation::None;
    else if (m.boundary == "edgeOnly")
        mesh.boundary = BoundaryInterpolation::EdgeOnly;
    else if (m.boundary == "edgeAndCorner")
        mesh.boundary = BoundaryInterpolation::EdgeAndCorner;
    else
        return ctx.fail("interpolateBoundary", "\"" + m.boundary + "\" is not none, edgeOnly or edgeAndCorner");
    return Status::ok();
}

struct VertexKey {
    uint32_t point;
    uint32_t bits[5];
    bool operator==(const VertexKey& o) const {
        return point == o.point && std::memcmp(bits, o.bits, sizeof bits) == 0;
    }
};
struct VertexKeyHash {
    size_t operator()(const VertexKey& k) const {
        uint64_t h = k.point * 0x9E3779B97F4A7C15ull;
        for (uint32_t b : k.bits) h = (h ^ b) * 0x100000001B3ull;
        return size_t(h);
    }
};

}  // namespace

Status buildMesh(const MeshData& m, const std::string& file, const InputOptions& options, bool loop, InputMesh& mesh,
                 Cage& cage, std::vector<std::string>& warnings) {
    const Context ctx{m, file};
    size_t triangleCount = 0;
    if (Status st = checkTopology(ctx, options, triangleCount); !st) return st;
    const size_t points = m.points.size() / 3, faces = m.counts.size(), corners = m.indices.size();
    PrimvarReader st{m.st}, color{m.displayColor};
    if (m.st.present && m.st.components != 2) return ctx.fail("primvars:st", "not 2 floats a value");
    if (m.displayColor.present && m.displayColor.components != 3)
        return ctx.fail("primvars:displayColor", "not 3 floats a value");
    if (Status s = st.check(ctx, "primvars:st", faces, points, corners); !s) return s;
    if (Status s = color.check(ctx, "primvars:displayColor", faces, points, corners); !s) return s;
    if (m.orientation != "rightHanded" && m.orientation != "leftHanded")
        return ctx.fail("orientation", "\"" + m.orientation + "\" is not rightHanded or leftHanded");
    const bool flip = m.orientation == "leftHanded";

    // Per face corner: its point and its cage vertex; points split only where st or
    // displayColor differ around them (first use first), then unused points.
    std::unordered_map<VertexKey, uint32_t, VertexKeyHash> vertexOf;
    const bool split = (st.mode == 1 || st.mode == 3) || (color.mode == 1 || color.mode == 3);
    std::vector<uint32_t> used(split ? points : 0, 0);
    // The faces' corners in winding order (leftHanded: c0 c(n-1) .. c1), as points,
    // as cage vertices and as UVs, then split by lt::triangulatePolygons as an OBJ's
    // polygons are, so a USD mesh and an OBJ of the same polygons bake alike.
    std::vector<uint32_t> counts(faces), polygonPoints, polygonCorners;
    std::vector<float> polygonUVs;
    polygonPoints.reserve(corners);
    polygonCorners.reserve(corners);
    mesh = InputMesh{};
    cage = Cage{};
    mesh.positions = m.points;
    // The cage vertex of a corner, its st (v flipped) and colour set as it is first met
    // (a split vertex has one st and one colour; unsplit, a point's are the same at
    // every corner).
    auto addVertex = [&](size_t f, size_t c, uint32_t p) {
        const float* uv = st.at(f, c, p);
        const float* rgb = color.at(f, c, p);
        uint32_t v = p;
        if (split) {
            VertexKey key{p, {}};
            if (uv) std::memcpy(key.bits, uv, 8);
            if (rgb) std::memcpy(key.bits + 2, rgb, 12);
            auto [it, added] = vertexOf.emplace(key, uint32_t(cage.controlVertex.size()));
            v = it->second;
            if (!added) return v;
            cage.controlVertex.push_back(p);
            used[p] = 1;
        }
        if (uv) {
            cage.texcoords.resize(std::max(cage.texcoords.size(), 2 * size_t(v) + 2), 0.0f);
            cage.texcoords[2 * size_t(v)] = uv[0];
            cage.texcoords[2 * size_t(v) + 1] = 1.0f - uv[1];
        }
        if (rgb) {
            cage.colors.resize(std::max(cage.colors.size(), 3 * size_t(v) + 3), 0.0f);
            std::memcpy(&cage.colors[3 * size_t(v)], rgb, 12);
        }
        return v;
    };
    if (!split) {
        cage.controlVertex.resize(points);
        for (uint32_t p = 0; p < points; ++p) cage.controlVertex[p] = p;
    }
    size_t corner = 0;
    for (size_t f = 0; f < faces; ++f) {
        const size_t n = size_t(m.counts[f]);
        counts[f] = uint32_t(n);
        for (size_t k = 0; k < n; ++k) {
            const size_t c = corner + (flip && k > 0 ? n - k : k);
            const uint32_t p = uint32_t(m.indices[c]);
            polygonPoints.push_back(p);
            polygonCorners.push_back(addVertex(f, c, p));
            if (const float* uv = st.at(f, c, p)) polygonUVs.insert(polygonUVs.end(), {uv[0], 1.0f - uv[1]});
        }
        corner += n;
    }
    const Triangulation split3 = triangulatePolygons(m.points, counts, polygonPoints);
    std::vector<uint32_t> firstTriangle(faces + 1, 0);
    mesh.faces.reserve(split3.corners.size());
    cage.indices.reserve(split3.corners.size());
    for (size_t i = 0; i < split3.corners.size(); ++i) {
        const uint32_t c = split3.corners[i];
        mesh.faces.push_back(polygonPoints[c]);
        cage.indices.push_back(polygonCorners[c]);
        if (st.mode >= 0)
            mesh.faceUVs.insert(mesh.faceUVs.end(), {polygonUVs[2 * size_t(c)], polygonUVs[2 * size_t(c) + 1]});
    }
    for (uint32_t polygon : split3.polygon) ++firstTriangle[size_t(polygon) + 1];
    for (size_t f = 0; f < faces; ++f) firstTriangle[f + 1] += firstTriangle[f];
    if (split)
        for (uint32_t p = 0; p < points; ++p)
            if (!used[p]) cage.controlVertex.push_back(p);  // in POSITION, in no triangle

    // Per vertex: its point's position; st and colour as set above (zeros where a point
    // is in no face).
    const size_t vertices = cage.controlVertex.size();
    cage.positions.resize(vertices * 3);
    for (size_t v = 0; v < vertices; ++v) std::memcpy(&cage.positions[v * 3], &m.points[cage.controlVertex[v] * 3], 12);
    if (st.mode >= 0) cage.texcoords.resize(vertices * 2, 0.0f);
    if (color.mode >= 0) cage.colors.resize(vertices * 3, 0.0f);
    if (!loop) return Status::ok();
    const size_t polygons = size_t(std::count_if(m.counts.begin(), m.counts.end(), [](int n) { return n > 3; }));
    if (polygons)
        warnings.push_back(file + ": " + m.path + ": " + std::to_string(polygons) +
                           " polygons with more than 3 sides were triangulated");
    if (!split3.unsplittable.empty())
        warnings.push_back(file + ": " + m.path + ": faceVertexCounts: face " + std::to_string(split3.unsplittable[0]) +
                           (split3.unsplittable.size() > 1
                                ? " (and " + std::to_string(split3.unsplittable.size() - 1) + " more)"
                                : std::string()) +
                           " has no triangulation without a triangle repeating another or an edge of three faces; "
                           "split along the diagonals the fewest other faces have (fix it in the mesh)");
    if (Status s = addTags(ctx, firstTriangle, mesh); !s) return s;
    if (options.boundary && *options.boundary != mesh.boundary)  // loopbake --boundary wins, said
        warnings.push_back(file + ": " + m.path + ": interpolateBoundary says " + boundaryOptionName(mesh.boundary) +
                           "; using --boundary " + boundaryOptionName(*options.boundary));
    if (options.boundary) mesh.boundary = *options.boundary;
    keepPolygonCorners(split3.polygonCorners, mesh);  // edge-and-corner on the faces as authored
    return Status::ok();
}

}  // namespace lt::usd
