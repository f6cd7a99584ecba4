// The control mesh, the source it was baked from, and the accuracy check against
// OpenSubdiv (looptess/tools/check.h; check_internal.h's checkAccuracy).
#include "check_internal.h"

#include "looptess/tools/file_io.h"
#include "random.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>

namespace lt {
namespace {

// The cross product of face `f`'s edges (twice its area, along its normal), in
// double; `longest` its longest edge.
void faceCross(const Asset& asset, uint32_t f, double n[3], double& longest) {
    const uint32_t* c = &asset.faces[3 * size_t(f)];
    double e[3][3];
    longest = 0;
    for (int i = 0; i < 3; ++i) {
        double len = 0;
        for (int k = 0; k < 3; ++k) {
            e[i][k] = double(asset.positions[3 * size_t(c[(i + 1) % 3]) + size_t(k)]) -
                      double(asset.positions[3 * size_t(c[i]) + size_t(k)]);
            len += e[i][k] * e[i][k];
        }
        longest = std::max(longest, std::sqrt(len));
    }
    n[0] = e[0][1] * e[1][2] - e[0][2] * e[1][1];
    n[1] = e[0][2] * e[1][0] - e[0][0] * e[1][2];
    n[2] = e[0][0] * e[1][1] - e[0][1] * e[1][0];
}

// Marks faces `f` and `g` (neighbours across an interior edge, so wound apart) as
// folded when their planes lie within ControlTopology::kFoldSine of each other
// facing opposite ways (the face doubled back onto the other), and a face with no
// area to speak of (under kFoldSine of its longest edge squared: its surface is
// squeezed between its neighbours').
void markFolded(const Asset& asset, uint32_t f, uint32_t g, ControlTopology& t) {
    double n[2][3], longest[2];
    faceCross(asset, f, n[0], longest[0]);
    faceCross(asset, g, n[1], longest[1]);
    double d = 0, x[3];
    for (int k = 0; k < 3; ++k) d += n[0][k] * n[1][k];
    x[0] = n[0][1] * n[1][2] - n[0][2] * n[1][1];
    x[1] = n[0][2] * n[1][0] - n[0][0] * n[1][2];
    x[2] = n[0][0] * n[1][1] - n[0][1] * n[1][0];
    const double sine = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    if (d < 0 && sine <= ControlTopology::kFoldSine * -d) t.folded[f] = t.folded[g] = 1;
    for (int i = 0; i < 2; ++i)
        if (std::sqrt(n[i][0] * n[i][0] + n[i][1] * n[i][1] + n[i][2] * n[i][2]) <
            ControlTopology::kFoldSine * longest[i] * longest[i])
            t.folded[i == 0 ? f : g] = 1;
}

}  // namespace

ControlTopology analyzeControlMesh(const Asset& asset) {
    ControlTopology t;
    const uint32_t faces = asset.faceCount();
    t.drawn.assign(faces, 0);
    t.folded.assign(faces, 0);
    for (const Level& level : asset.levels) {
        for (const RegularPatch& p : level.regular) t.drawn[p.param.baseFace] = 1;
        for (const IrregularFace& f : level.irregular) t.drawn[f.param.baseFace] = 1;
    }
    // Every drawn face's edges, sorted by undirected edge: (key, forward, face edge).
    struct Use {
        uint64_t key;
        bool forward;
        uint32_t faceEdge;
        bool operator<(const Use& o) const { return key < o.key; }
    };
    std::vector<Use> uses;
    for (uint32_t f = 0; f < faces; ++f) {
        if (!t.drawn[f]) continue;
        ++t.drawnFaces;
        for (uint32_t k = 0; k < 3; ++k) {
            const uint32_t a = asset.faces[3 * size_t(f) + k], b = asset.faces[3 * size_t(f) + (k + 1) % 3];
            uses.push_back({uint64_t(std::min(a, b)) << 32 | std::max(a, b), a < b, 3 * f + k});
        }
    }
    std::stable_sort(uses.begin(), uses.end());
    t.edgeKind.assign(size_t(faces) * 3, ControlTopology::kInterior);
    for (size_t i = 0; i < uses.size();) {
        size_t j = i;
        while (j < uses.size() && uses[j].key == uses[i].key) ++j;
        const size_t n = j - i;
        uint8_t kind = ControlTopology::kInterior;
        if (n == 1)
            kind = ControlTopology::kBoundary, ++t.boundaryEdges;
        else if (n > 2 || uses[i].forward == uses[i + 1].forward)
            kind = ControlTopology::kNonManifold, ++t.nonManifoldEdges;
        for (size_t k = i; k < j; ++k) t.edgeKind[uses[k].faceEdge] = kind;
        if (kind == ControlTopology::kInterior) markFolded(asset, uses[i].faceEdge / 3, uses[i + 1].faceEdge / 3, t);
        ++t.edges;
        i = j;
    }
    return t;
}

Status loadSource(const std::string& path, const SourceOptions& options, SourceMeshes& source) {
    source = SourceMeshes{};
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext != ".obj" && ext != ".gltf" && ext != ".glb")
        return Status::error(Status::Unsupported,
                             path + ": unsupported source format '" + ext + "' (expected .obj, .gltf or .glb)");
    std::vector<uint8_t> bytes;
    if (Status st = readFile(path, bytes); !st) return st;
    InputOptions io;  // as loopbake reads its input (apps/loopbake/bake_job.cpp)
    io.strict = options.strict;
    io.cleaning = options.strict ? InputCleaning::Refuse : InputCleaning::Repair;
    io.hardEdges = options.hardEdges;
    io.boundary = options.boundary;
    if (ext == ".obj") {
        source.meshes.resize(1);
        source.index = {-1};
        return parseObj(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path, io,
                        source.meshes[0]);
    }
    const std::string dir = std::filesystem::path(path).parent_path().string();
    GltfScene scene;
    if (Status st = parseGltfScene(bytes.data(), bytes.size(), path, dir.empty() ? "." : dir, io, scene); !st)
        return st;
    for (GltfScene::Mesh& m : scene.meshes) {
        source.meshes.push_back(std::move(m.mesh));
        source.index.push_back(m.index);
    }
    return Status::ok();
}

Status sourceMesh(const SourceMeshes& source, int64_t mesh, const std::string& path, const SourceOptions& options,
                  InputMesh& out) {
    size_t k = 0;
    while (k < source.index.size() && mesh >= 0 && source.index[k] != mesh) ++k;
    if (k == source.index.size())
        return Status::error(Status::BadInput, path + ": no mesh " + std::to_string(mesh) + " of triangles");
    out = source.meshes[k];
    Status st;
    if (!options.edits.empty()) {
        std::vector<uint8_t> json;
        st = readFile(options.edits, json);
        if (st)
            st = parseEditsJson(std::string_view(reinterpret_cast<const char*>(json.data()), json.size()),
                                options.edits, out);
    }
    if (st) st = checkInput(out, path);
    if (st && options.creaseAngle >= 0) addCreasesByAngle(out, options.creaseAngle);
    return st;
}

std::string compareControlMesh(const InputMesh& source, const Asset& asset) {
    std::ostringstream s;
    if (source.vertexCount() != asset.controlVertexCount() || source.faceCount() != asset.faceCount()) {
        s << "the source has " << source.vertexCount() << " vertices and " << source.faceCount()
          << " faces, the asset's control mesh " << asset.controlVertexCount() << " and " << asset.faceCount()
          << " (a different mesh, or baked with other options?)";
        return s.str();
    }
    for (size_t i = 0; i < source.positions.size(); ++i)
        if (std::memcmp(&source.positions[i], &asset.positions[i], sizeof(float)) != 0) {
            s << "control vertex " << i / 3 << " is at a different position in the source (coordinate " << i % 3 << ": "
              << source.positions[i] << " against " << asset.positions[i] << ")";
            return s.str();
        }
    for (size_t i = 0; i < source.faces.size(); ++i)
        if (source.faces[i] != asset.faces[i]) {
            s << "face " << i / 3 << " corner " << i % 3 << " is vertex " << source.faces[i] << " in the source, "
              << asset.faces[i] << " in the asset";
            return s.str();
        }
    if (source.faceUVs.size() != asset.faceUVs.size())
        return source.faceUVs.empty() ? "the asset has texture coordinates, the source none"
                                      : "the source has texture coordinates, the asset none";
    for (size_t i = 0; i < source.faceUVs.size(); ++i)
        if (std::memcmp(&source.faceUVs[i], &asset.faceUVs[i], sizeof(float)) != 0) {
            const size_t c = i / 2;
            s << "face " << c / 3 << " corner " << c % 3 << " has another texture coordinate in the source ("
              << source.faceUVs[2 * c] << ", " << source.faceUVs[2 * c + 1] << " against " << asset.faceUVs[2 * c]
              << ", " << asset.faceUVs[2 * c + 1] << ")";
            return s.str();
        }
    if (source.boundary != asset.boundary) {
        s << "the source's boundary rule is " << boundaryOptionName(source.boundary) << ", the asset's "
          << boundaryOptionName(asset.boundary) << " (baked with loopbake --boundary? give loopcheck the same)";
        return s.str();
    }
    if (source.creaseMethod != asset.creaseMethod) return "the source's crease method differs from the asset's";
    if (source.edits.size() != asset.editCount()) {
        s << "the source has " << source.edits.size() << " hierarchical edits, the asset " << asset.editCount()
          << " (baked with other edits, or a glTF source read without its --edits side-car?)";
        return s.str();
    }
    return "";
}

Status SourceOracle::build() { return fine.build(mesh, isolation); }

Status SourceOracle::atDepth(uint32_t depth, SourceOracle*& oracle) {
    oracle = this;
    if (int64_t(depth) >= int64_t(fine.editLevel())) return Status::ok();
    if (shallower.size() <= depth) shallower.resize(size_t(depth) + 1);
    std::unique_ptr<SourceOracle>& o = shallower[depth];
    if (!o) {
        auto built = std::make_unique<SourceOracle>();
        built->isolation = isolation;
        built->mesh = mesh;
        auto& edits = built->mesh.edits;
        edits.erase(std::remove_if(edits.begin(), edits.end(), [&](const auto& e) { return e.path.size() > depth; }),
                    edits.end());
        if (Status st = built->build(); !st) return st;
        o = std::move(built);
    }
    oracle = o.get();
    return Status::ok();
}

namespace {

double angleOf(double cosine) { return std::acos(std::clamp(cosine, -1.0, 1.0)); }

// The oracle's own remaining error after a step of `last` that followed one of
// `before` (two isolation levels each): geometric convergence with ratio q =
// last / before leaves last q / (1 - q); at least `last` (q clamped to 0.9).
double remaining(double last, double before) {
    const double q = before > 0 ? std::min(last / before, 0.9) : 0.0;
    return last * std::max(1.0, q / (1.0 - q));
}

// At corner k of base face `face` (corners (0,0), (1,0), (0,1)): the oracle's normal
// from finite differences of its positions, toward corners k + 1 and k + 2 by a
// parametric step of 1e-5 (so the normal faces like du x dv). PatchTable's du x dv
// can be far off at a base corner (21 degrees at a crease vertex between a dart's
// end and a corner, spot with --crease-angle 25; an F = 16 triangle there agrees
// with this one and with looptess to 1e-6). False when the oracle has no surface.
bool cornerNormalByDifferences(const OsdLimitSurface& oracle, int face, int k, double normal[3]) {
    const double corner[3][2] = {{0, 0}, {1, 0}, {0, 1}}, h = 1e-5;
    double p[3][3], n[3];
    for (int j = 0; j < 3; ++j) {
        const double* a = corner[k];
        const double* b = corner[(k + j) % 3];
        if (!oracle.evaluate(face, a[0] + h * (b[0] - a[0]), a[1] + h * (b[1] - a[1]), p[j], n)) return false;
    }
    double e1[3], e2[3];
    for (int c = 0; c < 3; ++c) e1[c] = p[1][c] - p[0][c], e2[c] = p[2][c] - p[0][c];
    normal[0] = e1[1] * e2[2] - e1[2] * e2[1];
    normal[1] = e1[2] * e2[0] - e1[0] * e2[2];
    normal[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const double len = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    if (!(len > 0)) return false;
    for (int c = 0; c < 3; ++c) normal[c] /= len;
    return true;
}

// Radians between `emitted` and the normal of `face`'s own corner `corner`
// refined (OsdCornerNormals), the smallest of: at the asset's depth (a spike's
// face normal, spec "Faces without a tangent plane"), at level 24 (a slit's), at
// its limit (a tangent plane's); NaN where the face has no normal (its corner has
// no area at any level: two of its corners coincide). False without the oracle
// (edits: it follows no edit) or when it fails.
bool refinedCornerAngle(SourceOracle& oracle, int face, int corner, const float emitted[3], double& angle) {
    if (!oracle.mesh.edits.empty()) return false;
    if (!oracle.corners.built() && !oracle.corners.build(oracle.mesh)) return false;
    angle = INFINITY;
    for (int levels : {int(oracle.assetDepth), 24, 80}) {
        OsdCornerNormals::Result r;
        const int drawn = levels == 80 ? -1 : int(oracle.assetDepth);  // the limit takes its own side
        if (!oracle.corners.normal(uint32_t(face), corner, levels, drawn, r)) return false;
        if (r.degenerate) {  // no normal to compare with: zero area at every level
            angle = NAN;
            return true;
        }
        double c = 0, len = 0;
        for (int k = 0; k < 3; ++k) {
            c += r.normal[k] * double(emitted[k]);
            len += double(emitted[k]) * double(emitted[k]);
        }
        angle = std::min(angle, len > 0 ? angleOf(c / std::sqrt(len)) : 3.141592653589793);
        if (r.levels < levels) break;  // converged: the limit
    }
    return true;
}

// How far float rounding alone may turn a normal computed from level-`depth` points
// (check.h): 2 eps |P| 2^depth / sigma_min radians, the rounding of a difference of
// two float points over their spacing. Past a radian the derivatives' rounding is
// as large as their smaller singular value and the float normal is undetermined (a
// fold, a zero-area face's limit): any passes.
double floatResolutionAngle(const double pos[3], const double du[3], const double dv[3], uint32_t depth) {
    double a = 0, b = 0, c = 0, p = 0;
    for (int k = 0; k < 3; ++k) {
        a += du[k] * du[k];
        b += du[k] * dv[k];
        c += dv[k] * dv[k];
        p += pos[k] * pos[k];
    }
    // Smaller eigenvalue of J^T J = [a b; b c], without cancellation: det / larger one.
    const double larger = 0.5 * (a + c) + std::sqrt(0.25 * (a - c) * (a - c) + b * b);
    const double det = a * c - b * b;
    const double sigmaMin = larger > 0 && det > 0 ? std::sqrt(det / larger) : 0.0;
    const double rounding = std::ldexp(std::sqrt(p) * 0x1p-23, int(depth));
    return sigmaMin > 0 ? rounding / sigmaMin : 3.141592653589793;
}

// How far float rounding alone may move a position computed from level-`depth`
// points (check.h): (2 + depth) eps |P|.
double floatResolutionDistance(const double pos[3], uint32_t depth) {
    return (2.0 + double(depth)) * 0x1p-24 * std::sqrt(pos[0] * pos[0] + pos[1] * pos[1] + pos[2] * pos[2]);
}

}  // namespace

namespace {

// A1's verdict on emitted vertex `i` (check.h, checkAccuracy).
struct VertexVerdict {
    bool limit = true;              // OpenSubdiv has a surface there
    double err = 0, normalErr = 0;  // |P - P_osd| (absolute), 1 - cos
    bool normalSkipped = false, oracleLimited = false, floatLimited = false;
};

VertexVerdict judgeVertex(SourceOracle& oracle, const Tessellation& soup, size_t i, uint32_t depth, double tolerance,
                          double angleTolerance) {
    VertexVerdict out;
    const int face = int(soup.face[i]);
    const float fu = soup.uv[2 * i], fv = soup.uv[2 * i + 1];
    double pos[3], nrm[3], du[3], dv[3];
    if (!oracle.fine.evaluate(face, fu, fv, pos, nrm, du, dv)) {
        out.limit = false;
        return out;
    }
    double err = 0, cosine = 0;
    for (int k = 0; k < 3; ++k) {
        const double d = pos[k] - double(soup.positions[3 * i + size_t(k)]);
        err += d * d;
        cosine += nrm[k] * double(soup.normals[3 * i + size_t(k)]);
    }
    err = std::sqrt(err);
    const bool ambiguous = oracle.fine.normalSignAmbiguous(face, fu, fv);
    if (ambiguous) cosine = std::fabs(cosine);
    double angle = angleOf(cosine);
    const int corner = baseCorner(fu, fv);
    double byDifferences[3];
    if (!(angle <= angleTolerance) && corner >= 0 &&
        cornerNormalByDifferences(oracle.fine, face, corner, byDifferences)) {
        double c = 0;
        for (int k = 0; k < 3; ++k) c += byDifferences[k] * double(soup.normals[3 * i + size_t(k)]);
        angle = std::min(angle, angleOf(ambiguous ? std::fabs(c) : c));
    }
    // Where the surface has no tangent plane (slits, cones, pinches, non-manifold
    // vertices, sharp corners whose sector holds several faces, wide crease or
    // boundary sectors) PatchTable's normal is undefined or wrong: the face's own
    // corner, refined, decides.
    const bool undefined = oracle.fine.normalUndefined(face, fu, fv);
    const bool patchNormal = nrm[0] != 0 || nrm[1] != 0 || nrm[2] != 0;
    bool refined = false, faceless = false;
    double byRefinement;
    if (corner >= 0 && (undefined || !patchNormal || !(angle <= angleTolerance)) &&
        refinedCornerAngle(oracle, face, corner, &soup.normals[3 * i], byRefinement)) {
        angle = undefined || !patchNormal ? byRefinement : std::min(angle, byRefinement);
        refined = true;
        faceless = std::isnan(byRefinement);
    }
    if (!std::isfinite(err)) err = INFINITY;  // NaN never passes, even with slack
    if (!std::isfinite(angle)) angle = 3.141592653589793;
    if (!(err <= tolerance) || (!refined && !(angle <= angleTolerance))) {
        // Near extraordinary vertices and irregular creases the oracle itself still
        // converges (its corner normals too): allow its remaining error,
        // extrapolated from isolation - 4, - 2 and isolation (see check.h).
        if (!oracle.coarse.built()) {
            oracle.coarse.build(oracle.mesh, std::max(1, oracle.isolation - 2));
            oracle.coarser.build(oracle.mesh, std::max(1, oracle.isolation - 4));
        }
        double p8[3], n8[3], p6[3], n6[3];
        if (oracle.coarse.evaluate(face, fu, fv, p8, n8) && oracle.coarser.evaluate(face, fu, fv, p6, n6)) {
            double d1 = 0, d0 = 0, c1 = 0, c0 = 0;
            for (int k = 0; k < 3; ++k) {
                d1 += (pos[k] - p8[k]) * (pos[k] - p8[k]);
                d0 += (p8[k] - p6[k]) * (p8[k] - p6[k]);
                c1 += nrm[k] * n8[k];
                c0 += n8[k] * n6[k];
            }
            const double slack = remaining(std::sqrt(d1), std::sqrt(d0));
            const double angleSlack = remaining(angleOf(c1), angleOf(c0));
            out.oracleLimited = err <= tolerance + slack && angle <= angleTolerance + angleSlack;
            err = std::max(0.0, err - slack);
            angle = std::max(0.0, angle - angleSlack);
        }
    }
    // Float resolution of a position: (2 + depth) eps |P| (check.h).
    if (!(err <= tolerance)) {
        const double floatSlack = floatResolutionDistance(pos, depth);
        out.floatLimited = err <= tolerance + floatSlack;
        err = std::max(0.0, err - floatSlack);
    }
    // Float resolution, from PatchTable's derivatives where they mean something.
    if (!(angle <= angleTolerance) && !undefined && patchNormal) {
        const double floatSlack = floatResolutionAngle(pos, du, dv, depth);
        out.floatLimited = floatSlack >= 1.0 || angle <= angleTolerance + floatSlack;
        angle = floatSlack >= 1.0 ? 0.0 : std::max(0.0, angle - floatSlack);
    }
    out.err = err;
    out.normalErr = 1.0 - std::cos(angle);  // also catches flipped normals
    if ((!refined && (undefined || !patchNormal)) || faceless) {
        out.normalErr = 0;
        out.normalSkipped = true;
    }
    return out;
}

}  // namespace

bool cageOracle(const Asset& asset, SourceOracle& oracle, std::vector<char>& smoothVertex) {
    if (asset.editCount() > 0 || asset.levels.size() < 2) return false;
    oracle.mesh = InputMesh{};
    oracle.mesh.positions = asset.positions;
    oracle.mesh.faces = asset.faces;
    oracle.mesh.boundary = asset.boundary;
    oracle.mesh.creaseMethod = asset.creaseMethod;
    oracle.assetDepth = asset.maxDepth();
    if (!oracle.build()) return false;
    const Refinement& r = asset.levels[1].refinement;
    std::vector<char> masked(r.vertexPointCount(), 0);
    for (uint32_t k : r.maskedVertex) masked[k] = 1;
    smoothVertex.assign(asset.controlVertexCount(), 0);
    for (uint32_t i = 0; i < r.vertexPointCount(); ++i)
        if (!masked[i]) smoothVertex[r.vertexParent[i]] = 1;
    return true;
}

bool normalConfirmed(SourceOracle& oracle, const Tessellation& soup, size_t vertex, uint32_t depth,
                     const CheckSettings& settings) {
    const VertexVerdict v = judgeVertex(oracle, soup, vertex, depth, INFINITY, angleOf(1.0 - settings.normalTolerance));
    return v.limit && !v.normalSkipped && v.normalErr <= settings.normalTolerance;
}

void checkAccuracy(SourceOracle& oracle, const Tessellation& soup, uint32_t depth, double diagonal,
                   const CheckSettings& settings, uint64_t seed, AccuracyResult& out) {
    out = AccuracyResult{};
    out.ran = true;
    out.referenceEdits = oracle.fine.editCount();
    out.referenceEditLevel = oracle.fine.editLevel();
    const size_t n = soup.vertexCount();
    if (n == 0 || !oracle.fine.built()) return;
    const uint64_t samples = std::max<uint64_t>(1, std::min<uint64_t>(settings.accuracySamples, n));
    const double tolerance = settings.positionTolerance * diagonal;
    const double angleTolerance = angleOf(1.0 - settings.normalTolerance);
    // Vertex i judged: counted, its verdict added to `out`.
    auto judge = [&](size_t i) {
        ++out.sampled;
        out.corners += baseCorner(soup.uv[2 * i], soup.uv[2 * i + 1]) >= 0;
        auto where = [&] {
            std::ostringstream w;
            w << "vertex " << i << " face " << soup.face[i] << " (u, v) = (" << soup.uv[2 * i] << ", "
              << soup.uv[2 * i + 1] << ")";
            return w.str();
        };
        const VertexVerdict v = judgeVertex(oracle, soup, i, depth, tolerance, angleTolerance);
        if (!v.limit) {
            if (out.noLimit++ == 0 && out.firstFailure.empty())
                out.firstFailure = where() + ": OpenSubdiv has no limit surface there";
            return;
        }
        out.oracleLimited += v.oracleLimited;
        out.floatLimited += v.floatLimited;
        out.normalsSkipped += v.normalSkipped;
        out.maxPositionError = std::max(out.maxPositionError, v.err / diagonal);
        if (std::isfinite(v.normalErr)) out.maxNormalError = std::max(out.maxNormalError, v.normalErr);
        const bool posBad = !(v.err <= tolerance), normalBad = !(v.normalErr <= settings.normalTolerance);
        out.positionFailures += posBad;
        out.normalFailures += normalBad;
        if ((posBad || normalBad) && out.firstFailure.empty()) {
            std::ostringstream s;
            s << where() << ": position off by " << v.err / diagonal << " of the diagonal, 1 - cos = " << v.normalErr;
            out.firstFailure = s.str();
        }
    };
    // One vertex in each of `samples` strata (stratum s: vertices [s n / samples,
    // (s + 1) n / samples)), and between them every vertex at a base corner, so that
    // vertices are judged in order and the first failure is the lowest one judged.
    // Corners are where single-vertex defects live (degenerate corners, stencils of
    // one vertex), only three per base face: a sample would miss them.
    Random rng(seed);
    size_t next = 0;  // the first vertex not yet passed
    auto cornersUpTo = [&](size_t end) {
        for (; next < end; ++next)
            if (baseCorner(soup.uv[2 * next], soup.uv[2 * next + 1]) >= 0) judge(next);
    };
    for (uint64_t s = 0; s < samples; ++s) {
        const size_t lo = size_t(s * n / samples), hi = size_t((s + 1) * n / samples);
        const size_t i = lo + size_t(rng.below(std::max<size_t>(1, hi - lo)));
        cornersUpTo(i);
        judge(i);
        next = i + 1;
    }
    cornersUpTo(n);
}

}  // namespace lt
