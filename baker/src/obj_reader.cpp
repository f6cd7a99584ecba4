// obj_reader.cpp -- lt::parseObj: Wavefront OBJ text with OpenSubdiv's tags.
//
// Grammar accepted (one statement per line, '#' starts a comment):
//   v x y z [more numbers]      position (extra numbers, e.g. w or colour, ignored)
//   vt u [v [w]]                texture coordinate
//   f c c c [c ...]             c = v | v/vt | v//vn | v/vt/vn, 1-based or negative
//   t name nI/nF/nS ints floats strings    OpenSubdiv tag, indices 0-based:
//     crease N/1/0 a0 b0 a1 b1 .. s   N/2 edges (a_i, b_i), one sharpness (N even)
//     crease N/(N/2)/0 a0 b0 .. s0 .. one sharpness per edge
//       (vertex pairs, as OpenSubdiv's own shape reader far_utils.h reads them)
//     corner N/1/0 v.. s  |  corner N/N/0 v.. s..
//     hole N/0/0 f..                  polygon indices of this file
//     interpolateboundary 1/0/0 k     0 none, 1 edge-and-corner, 2 edge-only
//     creasemethod 0/0/1 chaikin|normal
//     vertexedit nI/nF/3 paths.. floats.. add|set|subtract P value   (Hbr's form)
//       paths `pathlength face c1 .. ck vertex`, pathlength = k + 2, face a triangle
//       polygon of this file; 3 floats per path (extras warn and are ignored, as
//       Hbr's hbr_utils.h ignores them). edgeedit and faceedit are rejected.
//   vn o g s usemtl mtllib           ignored
// Anything else warns once per keyword (statements) or tag name (tags).
//
// Safety: every count declared in the text is only trusted as far as the line
// actually supplies items, so allocations stay proportional to the input size;
// options.limits.maxVertices and maxFaces stop the parse as soon as they are passed.
#include "looptess/tools/baker.h"
#include "looptess/tools/triangulate.h"
#include "mesh_clean.h"
#include "resource_limits.h"
#include "obj_text.h"
#include "text.h"

#include <algorithm>
#include <cassert>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace lt {
namespace {

using namespace obj;

constexpr size_t kMaxUnknownKeywords = 16;  // distinct keywords warned about

class ObjParser {
public:
    ObjParser(const std::string& name, const InputOptions& options, InputMesh& mesh)
        : name_(name), options_(options), mesh_(mesh), cleaner_(mesh.positions, options.cleaning) {}

    Status run(std::string_view text);

private:
    Status fail(const std::string& what) const {
        return Status::error(Status::BadInput, name_ + ":" + std::to_string(line_) + ": " + what);
    }
    Status failAt(size_t line, const std::string& what) const {
        return Status::error(Status::BadInput, name_ + ":" + std::to_string(line) + ": " + what);
    }
    void warn(const std::string& what) { mesh_.warnings.push_back(name_ + ": " + what); }
    void warnUnknown(const std::string& kind, std::string_view word);

    Status statement(std::string_view line);
    Status readNumbers(Tokens& tokens, const char* what, size_t minCount, size_t maxCount, float* out, size_t& count);
    Status vertex(Tokens& tokens);
    Status texcoord(Tokens& tokens);
    Status resolve(std::string_view tok, size_t count, const char* what, uint32_t& out);
    Status corner(std::string_view tok, uint32_t& v, int64_t& vt);
    Status face(Tokens& tokens);
    void triangulate();
    Status tag(Tokens& tokens);
    Status checkTagShape(const Tag& t);
    Status readVertexEdit(Tag& t);
    Status applyTag(const Tag& t);
    Status applyCrease(const Tag& t);
    Status applyCorner(const Tag& t);
    Status applyHole(const Tag& t);
    Status applyVertexEdit(const Tag& t);
    Status sharpness(const Tag& t, float s);
    Status vertexIndex(const Tag& t, int64_t i, uint32_t& out);
    void finishUVs();
    Status settleZeroArea();
    static std::string lineName(uint64_t line) { return "line " + std::to_string(line); }

    const std::string& name_;
    const InputOptions& options_;
    InputMesh& mesh_;
    size_t line_ = 0;

    std::vector<float> uvs_;              // 2 per vt
    std::vector<uint32_t> polyVerts_;     // scratch: current face
    std::vector<int64_t> polyUVs_;        // scratch: vt index per corner, -1 none
    std::vector<uint32_t> polyFirstTri_;  // triangle range of polygon i: [i, i+1), once triangulated
    // Every polygon's corners kept by cleaning, in file order (triangulate() splits
    // them once all are read): keptCounts_ per polygon (0: dropped), keptVerts_ and
    // keptUVs_ (vt index, -1 none) per corner.
    std::vector<uint32_t> keptCounts_, keptVerts_;
    std::vector<int64_t> keptUVs_;
    size_t triangles_ = 0;  // what keptCounts_ will become
    FaceCleaner cleaner_;
    std::vector<uint32_t> kept_;            // scratch: the current face's corners kept
    std::vector<uint32_t> polygonCorners_;  // Triangulation::polygonCorners
    struct Polygon {
        uint32_t line;
        uint8_t fate;  // FaceCleaner::Fate, final once settleZeroArea ran
        bool uv;
    };
    std::vector<Polygon> polygons_;               // every polygon of the file
    std::vector<FaceCleaner::Pending> zeroArea_;  // for settleZeroArea
    std::vector<uint64_t> removedEdges_;          // edges of the polygons cleaning changed
    std::vector<std::string> unknown_;            // keywords already warned about
    bool unknownOverflow_ = false;
    std::vector<Tag> tags_;
    std::vector<uint8_t> holePolygon_;  // polygon already made a hole
    size_t boundaryTag_ = 0;            // the line of the interpolateboundary tag applied last
};

void ObjParser::warnUnknown(const std::string& kind, std::string_view word) {
    std::string key = kind + " " + std::string(word);
    for (const std::string& k : unknown_)
        if (k == key) return;
    if (unknown_.size() >= kMaxUnknownKeywords) {
        if (!unknownOverflow_) warn("more unknown statements or tags; not reported");
        unknownOverflow_ = true;
        return;
    }
    unknown_.push_back(key);
    warn("line " + std::to_string(line_) + ": ignoring unknown " + kind + " '" + printable(word) + "'");
}

Status ObjParser::readNumbers(Tokens& tokens, const char* what, size_t minCount, size_t maxCount, float* out,
                              size_t& count) {
    count = 0;
    std::string_view tok;
    while (tokens.next(tok)) {
        float f = 0;
        NumResult r = parseFloat(tok, f);
        if (r == NumResult::Bad) return fail("bad number '" + printable(tok) + "' in " + what);
        if (r == NumResult::OutOfRange) return fail("number '" + printable(tok) + "' out of range in " + what);
        if (!std::isfinite(f)) return fail(std::string(what) + " has a non-finite coordinate '" + printable(tok) + "'");
        if (count < maxCount) out[count] = f;
        ++count;
    }
    if (count < minCount)
        return fail(std::string(what) + " needs at least " + std::to_string(minCount) + " numbers, has " +
                    std::to_string(count));
    return Status::ok();
}

Status ObjParser::vertex(Tokens& tokens) {
    float p[3] = {};
    size_t n = 0;
    if (Status st = readNumbers(tokens, "vertex", 3, 3, p, n); !st) return st;
    const size_t count = mesh_.positions.size() / 3;
    if (count >= options_.limits.maxVertices)
        return fail(limitMessage("at least " + std::to_string(count + 1), "vertices", options_.limits.maxVertices,
                                 "--max-vertices"));
    if (count >= std::numeric_limits<uint32_t>::max() - 1) return fail("too many vertices");
    mesh_.positions.insert(mesh_.positions.end(), p, p + 3);
    return Status::ok();
}

Status ObjParser::texcoord(Tokens& tokens) {
    float uv[2] = {};
    size_t n = 0;
    if (Status st = readNumbers(tokens, "texture coordinate", 1, 2, uv, n); !st) return st;
    // OBJ's v runs up from the bottom of the image, glTF's down from the top:
    // InputMesh::faceUVs use glTF's convention.
    uv[1] = 1.0f - uv[1];
    uvs_.insert(uvs_.end(), uv, uv + 2);
    return Status::ok();
}

// OBJ index `tok` (1-based, or negative relative to the `count` items so far).
Status ObjParser::resolve(std::string_view tok, size_t count, const char* what, uint32_t& out) {
    int64_t i = 0;
    if (!parseInt(tok, i)) return fail("bad " + std::string(what) + " index '" + printable(tok) + "'");
    if (i == 0) return fail(std::string(what) + " index 0 (OBJ indices start at 1)");
    int64_t n = int64_t(count);
    if (i > n || i < -n)
        return fail(std::string(what) + " index " + std::to_string(i) + " out of range (" + std::to_string(count) +
                    " defined so far)");
    out = uint32_t(i > 0 ? i - 1 : n + i);
    return Status::ok();
}

// One face corner: v, v/vt, v//vn or v/vt/vn. vt is -1 when absent.
Status ObjParser::corner(std::string_view tok, uint32_t& v, int64_t& vt) {
    std::string_view parts[3];
    size_t nparts = 0;
    for (size_t start = 0;;) {
        size_t slash = tok.find('/', start);
        if (nparts == 3) return fail("bad face corner '" + printable(tok) + "'");
        parts[nparts++] = tok.substr(start, slash == std::string_view::npos ? slash : slash - start);
        if (slash == std::string_view::npos) break;
        start = slash + 1;
    }
    if (Status st = resolve(parts[0], mesh_.positions.size() / 3, "vertex", v); !st) return st;
    vt = -1;
    if (nparts >= 2 && !parts[1].empty()) {
        uint32_t t = 0;
        if (Status st = resolve(parts[1], uvs_.size() / 2, "texture coordinate", t); !st) return st;
        vt = t;
    }
    int64_t vn = 0;  // normals are ignored, but must be well-formed
    if ((nparts == 2 && parts[1].empty()) || (nparts == 3 && !parseInt(parts[2], vn)))
        return fail("bad face corner '" + printable(tok) + "'");
    return Status::ok();
}

Status ObjParser::face(Tokens& tokens) {
    polyVerts_.clear();
    polyUVs_.clear();
    std::string_view tok;
    while (tokens.next(tok)) {
        uint32_t v = 0;
        int64_t vt = -1;
        if (Status st = corner(tok, v, vt); !st) return st;
        polyVerts_.push_back(v);
        polyUVs_.push_back(vt);
    }
    size_t n = polyVerts_.size();
    if (n < 3) return fail("face has " + std::to_string(n) + " vertices, fewer than 3");
    size_t withUV = 0;
    for (int64_t t : polyUVs_) withUV += t >= 0;
    if (withUV != 0 && withUV != n) return fail("face mixes corners with and without texture coordinates");
    if (n > 3 && options_.strict)
        return fail("face has " + std::to_string(n) + " vertices; strict mode accepts only triangles");
    const FaceCleaner::Fate fate = cleaner_.clean(polyVerts_.data(), n, line_, kept_);
    if (fate != FaceCleaner::Fate::Kept) {
        if (options_.cleaning == InputCleaning::Refuse && fate != FaceCleaner::Fate::ZeroArea)
            return fail("face " + cleaner_.defect(fate, lineName));
        for (size_t k = 0; k < n; ++k) removedEdges_.push_back(undirectedEdge(polyVerts_[k], polyVerts_[(k + 1) % n]));
    }
    polygons_.push_back({uint32_t(line_), uint8_t(fate), withUV != 0});
    n = kept_.size();
    keptCounts_.push_back(uint32_t(n));
    if (n == 0) return Status::ok();          // dropped: polygon numbers stay the file's
    if (fate == FaceCleaner::Fate::ZeroArea)  // its first triangle is set by triangulate()
        zeroArea_.push_back({line_, 0, uint32_t(n - 2), cleaner_.lastRepaired()});
    triangles_ += n - 2;
    if (triangles_ > options_.limits.maxFaces)
        return fail(limitMessage("at least " + std::to_string(triangles_), "faces (triangles)",
                                 options_.limits.maxFaces, "--max-faces"));
    if (keptVerts_.size() + n >= std::numeric_limits<uint32_t>::max()) return fail("too many faces");
    for (uint32_t k : kept_) {
        keptVerts_.push_back(polyVerts_[k]);
        keptUVs_.push_back(polyUVs_[k]);
    }
    return Status::ok();
}

// Splits every polygon kept (triangulatePolygons: no split that repeats a triangle or
// gives an edge a third face where another exists; a warning names each polygon
// without one) into mesh_.faces, in file order, and sets polyFirstTri_ and the
// zero-area polygons' first triangles. Once a polygon has texture coordinates,
// faceUVs has 6 per triangle (zeros for a polygon without, until finishUVs), so that
// settleZeroArea can drop triangles from both.
void ObjParser::triangulate() {
    Triangulation t = triangulatePolygons(mesh_.positions, keptCounts_, keptVerts_);
    polygonCorners_ = std::move(t.polygonCorners);
    bool uv = false;
    for (size_t p = 0; p < polygons_.size(); ++p) uv |= polygons_[p].uv && keptCounts_[p] != 0;
    mesh_.faces.reserve(t.corners.size());
    if (uv) mesh_.faceUVs.reserve(2 * t.corners.size());
    for (uint32_t c : t.corners) {
        mesh_.faces.push_back(keptVerts_[c]);
        if (!uv) continue;
        const int64_t vt = keptUVs_[c];
        mesh_.faceUVs.push_back(vt < 0 ? 0.0f : uvs_[2 * size_t(vt)]);
        mesh_.faceUVs.push_back(vt < 0 ? 0.0f : uvs_[2 * size_t(vt) + 1]);
    }
    polyFirstTri_.assign(1, 0);
    for (size_t p = 0, z = 0; p < polygons_.size(); ++p) {
        const uint32_t n = keptCounts_[p], first = polyFirstTri_.back();
        if (n != 0 && polygons_[p].fate == uint8_t(FaceCleaner::Fate::ZeroArea)) zeroArea_[z++].first = first;
        polyFirstTri_.push_back(first + (n >= 3 ? n - 2 : 0));
    }
    constexpr size_t kNamed = 8;  // keptCounts_ has every polygon: t numbers them as the file does
    for (size_t i = 0; i < t.unsplittable.size() && i < kNamed; ++i) {
        const uint32_t p = t.unsplittable[i];
        warn("line " + std::to_string(polygons_[p].line) + ": polygon " + std::to_string(p) + " of " +
             std::to_string(keptCounts_[p]) +
             " sides has no triangulation without a triangle repeating another or an edge of three faces; "
             "split along the diagonals the fewest other faces have (fix it in the mesh)");
    }
    if (t.unsplittable.size() > kNamed)
        warn(std::to_string(t.unsplittable.size() - kNamed) + " more polygons have no such triangulation");
    keptCounts_ = {}, keptVerts_ = {}, keptUVs_ = {};
}

Status ObjParser::checkTagShape(const Tag& t) {
    if (tagShapeOk(t)) return Status::ok();
    const size_t ni = t.ints.size(), nf = t.floats.size(), ns = t.strings.size();
    return fail("malformed tag counts " + std::to_string(ni) + "/" + std::to_string(nf) + "/" + std::to_string(ns) +
                " for '" + t.name + "'");
}

Status ObjParser::sharpness(const Tag& t, float s) {
    if (s < 0) return failAt(t.line, "negative sharpness " + formatFloat(s) + " in '" + t.name + "' tag");
    return Status::ok();
}

Status ObjParser::tag(Tokens& tokens) {
    Tag t;
    t.line = line_;
    std::string_view tok, counts;
    if (!tokens.next(tok)) return fail("tag without a name");
    t.name = std::string(tok);
    if (t.name == "edgeedit" || t.name == "faceedit")
        return fail("'" + t.name + "' tags (hierarchical " + (t.name == "edgeedit" ? "edge sharpness" : "face") +
                    " edits) are not supported; ignoring them would change the surface");
    bool known = t.name == "crease" || t.name == "corner" || t.name == "hole" || t.name == "interpolateboundary" ||
                 t.name == "creasemethod" || t.name == "vertexedit";
    if (!known) {
        warnUnknown("tag", tok);
        return Status::ok();
    }
    int64_t n[3] = {};
    size_t s1 = 0, s2 = 0;
    if (tokens.next(counts)) {
        s1 = counts.find('/');
        s2 = s1 == std::string_view::npos ? s1 : counts.find('/', s1 + 1);
    }
    if (counts.empty() || s2 == std::string_view::npos || !parseInt(counts.substr(0, s1), n[0]) ||
        !parseInt(counts.substr(s1 + 1, s2 - s1 - 1), n[1]) || !parseInt(counts.substr(s2 + 1), n[2]) || n[0] < 0 ||
        n[1] < 0 || n[2] < 0)
        return fail("bad tag counts '" + printable(counts) + "' (expected ints/floats/strings)");
    // Items are read one by one: a huge declared count fails at the end of the line.
    for (int64_t i = 0; i < n[0]; ++i) {
        int64_t v = 0;
        if (!tokens.next(tok)) return fail("tag '" + t.name + "' is missing integer arguments");
        if (!parseInt(tok, v)) return fail("bad integer '" + printable(tok) + "' in tag");
        t.ints.push_back(v);
    }
    for (int64_t i = 0; i < n[1]; ++i) {
        float f = 0;
        if (!tokens.next(tok)) return fail("tag '" + t.name + "' is missing float arguments");
        if (parseFloat(tok, f) != NumResult::Ok || std::isnan(f))
            return fail("bad number '" + printable(tok) + "' in tag");
        t.floats.push_back(f);
    }
    for (int64_t i = 0; i < n[2]; ++i) {
        if (!tokens.next(tok)) return fail("tag '" + t.name + "' is missing string arguments");
        t.strings.emplace_back(tok);
    }
    if (tokens.next(tok)) return fail("tag '" + t.name + "' has more arguments than its counts declare");
    if (t.name == "vertexedit") {
        if (Status st = readVertexEdit(t); !st) return st;
        tags_.push_back(std::move(t));
        return Status::ok();
    }
    if (Status st = checkTagShape(t); !st) return st;
    for (float f : t.floats)
        if (Status st = sharpness(t, f); !st) return st;
    tags_.push_back(std::move(t));
    return Status::ok();
}

// Splits a vertexedit tag into its edits (faces still polygon indices, mapped by
// applyVertexEdit). Only what Hbr applies to positions is accepted, one triple
// `add|set|subtract P value`: anything else would change the surface unseen.
Status ObjParser::readVertexEdit(Tag& t) {
    const std::string tagName = "'vertexedit' tag", form = "one 'add|set|subtract P value' triple";
    if (t.strings.size() != 3)
        return fail(tagName + " has " + std::to_string(t.strings.size()) + " strings; it needs " + form);
    const char* const ops[] = {"set", "add", "subtract"};  // EditOp's order
    const auto op = std::find(std::begin(ops), std::end(ops), t.strings[0]) - std::begin(ops);
    if (op == 3 || t.strings[1] != "P" || t.strings[2] != "value")
        return fail(tagName + ": '" + printable(t.strings[0] + " " + t.strings[1] + " " + t.strings[2]) +
                    "' is not supported (sharpness and attributes other than P are not); it needs " + form);
    const std::vector<int64_t>& ints = t.ints;
    for (size_t k = 0; k < ints.size();) {
        const int64_t len = ints[k];
        if (len < 2 || uint64_t(len) > ints.size() - k - 1)
            return fail(tagName + ": path length " + std::to_string(len) + " at integer " + std::to_string(k) +
                        " does not fit the tag's " + std::to_string(ints.size()) +
                        " integers (a path is 'pathlength face child.. vertex', pathlength >= 2)");
        const auto first = ints.begin() + ptrdiff_t(k + 2), last = ints.begin() + ptrdiff_t(k + size_t(len));
        const int64_t face = ints[k + 1], vertex = *last;
        const std::string what = tagName + ": edit (" + editText(face, first, last, vertex) + ")";
        if (face < 0 || face > int64_t(std::numeric_limits<uint32_t>::max()))
            return fail(what + " names face " + std::to_string(face) + ", out of range");
        InputMesh::VertexEdit e;
        for (auto c = first; c != last; ++c) {
            if (*c < 0 || *c > 3) return fail(what + " has child " + std::to_string(*c) + "; children are 0..3");
            e.path.push_back(uint8_t(*c));
        }
        if (vertex < 0 || vertex > 2)
            return fail(what + " has vertex " + std::to_string(vertex) + "; triangles have corners 0..2");
        e.face = uint32_t(face);
        e.vertex = uint8_t(vertex);
        e.op = EditOp(op);
        t.edits.push_back(std::move(e));
        k += size_t(len) + 1;
    }
    const size_t paths = t.edits.size(), need = 3 * paths;
    if (paths == 0 || t.floats.size() < need)
        return fail(tagName + " has " + std::to_string(t.floats.size()) + " floats for " + std::to_string(paths) +
                    " paths; it needs at least one path and 3 floats (x y z) per path");
    if (t.floats.size() > need)
        warn("line " + std::to_string(line_) + ": 'vertexedit' tag has " + std::to_string(t.floats.size()) +
             " floats for " + std::to_string(paths) + " paths; using the first " + std::to_string(need) +
             " (3 per path, as OpenSubdiv's Hbr reads them)");
    for (size_t i = 0; i < need; ++i) {
        if (!std::isfinite(t.floats[i])) return fail(tagName + " has a non-finite value " + formatFloat(t.floats[i]));
        t.edits[i / 3].value[i % 3] = t.floats[i];
    }
    return Status::ok();
}

Status ObjParser::vertexIndex(const Tag& t, int64_t i, uint32_t& out) {
    if (i < 0 || uint64_t(i) >= mesh_.positions.size() / 3)
        return failAt(t.line, "'" + t.name + "' tag index " + std::to_string(i) + " out of range (" +
                                  std::to_string(mesh_.positions.size() / 3) + " vertices)");
    out = uint32_t(i);
    return Status::ok();
}

// Vertex pairs (a0,b0) (a1,b1) ...: one edge each.
Status ObjParser::applyCrease(const Tag& t) {
    for (size_t e = 0; e + 1 < t.ints.size(); e += 2) {
        InputMesh::Crease c{};
        if (Status st = vertexIndex(t, t.ints[e], c.a); !st) return st;
        if (Status st = vertexIndex(t, t.ints[e + 1], c.b); !st) return st;
        c.sharpness = t.floats.size() == 1 ? t.floats[0] : t.floats[e / 2];
        mesh_.creases.push_back(c);
    }
    return Status::ok();
}

Status ObjParser::applyCorner(const Tag& t) {
    for (size_t k = 0; k < t.ints.size(); ++k) {
        InputMesh::Corner c{};
        if (Status st = vertexIndex(t, t.ints[k], c.vertex); !st) return st;
        c.sharpness = t.floats.size() == 1 ? t.floats[0] : t.floats[k];
        mesh_.corners.push_back(c);
    }
    return Status::ok();
}

// Polygon indices of the file -> every triangle the polygon became, once per polygon
// however often it is named (repeats of a big polygon would otherwise make the hole
// list grow with the product of two input sizes).
Status ObjParser::applyHole(const Tag& t) {
    size_t polygons = polyFirstTri_.size() - 1;
    if (holePolygon_.size() != polygons) holePolygon_.assign(polygons, 0);
    for (int64_t p : t.ints) {
        if (p < 0 || uint64_t(p) >= polygons)
            return failAt(t.line, "'hole' tag index " + std::to_string(p) + " out of range (" +
                                      std::to_string(polygons) + " faces)");
        if (holePolygon_[size_t(p)]) continue;
        holePolygon_[size_t(p)] = 1;
        for (uint32_t tri = polyFirstTri_[size_t(p)]; tri < polyFirstTri_[size_t(p) + 1]; ++tri)
            mesh_.holes.push_back(tri);
    }
    return Status::ok();
}

// Polygon indices of the file -> triangle indices. A polygon with more than 3 sides
// was triangulated, and one input cleaning changed has other corners: a path below
// either names no sub-triangle the author meant.
Status ObjParser::applyVertexEdit(const Tag& t) {
    const size_t polygons = polyFirstTri_.size() - 1;
    for (const InputMesh::VertexEdit& e : t.edits) {
        const std::string what =
            "'vertexedit' tag: edit (" + editText(e.face, e.path.begin(), e.path.end(), e.vertex) + ")";
        if (e.face >= polygons)
            return failAt(t.line, what + " names face " + std::to_string(e.face) + ", out of range (" +
                                      std::to_string(polygons) + " faces)");
        const uint32_t tri = polyFirstTri_[e.face], triangles = polyFirstTri_[e.face + 1] - tri;
        if (polygons_[e.face].fate != uint8_t(FaceCleaner::Fate::Kept))
            return failAt(t.line, what + " names polygon " + std::to_string(e.face) + ", which input cleaning " +
                                      (triangles ? "repaired" : "dropped") +
                                      " (see its warning); edits need "
                                      "the polygon as written: fix it in the mesh");
        if (triangles != 1)
            return failAt(t.line, what + " names polygon " + std::to_string(e.face) + ", which has " +
                                      std::to_string(triangles + 2) +
                                      " sides and was triangulated; edits need a triangle");
        mesh_.edits.push_back(e);
        mesh_.edits.back().face = tri;
    }
    return Status::ok();
}

Status ObjParser::applyTag(const Tag& t) {
    if (t.name == "crease") return applyCrease(t);
    if (t.name == "corner") return applyCorner(t);
    if (t.name == "hole") return applyHole(t);
    if (t.name == "vertexedit") return applyVertexEdit(t);
    if (t.name == "interpolateboundary") {
        if (t.ints[0] < 0 || t.ints[0] > 2)
            return failAt(t.line, "interpolateboundary must be 0, 1 or 2, not " + std::to_string(t.ints[0]));
        mesh_.boundary = BoundaryInterpolation(uint8_t(t.ints[0]));
        boundaryTag_ = t.line;
        return Status::ok();
    }
    assert(t.name == "creasemethod");
    if (t.strings[0] != "chaikin" && t.strings[0] != "normal")
        return failAt(t.line, "creasemethod must be 'chaikin' or 'normal', not '" + printable(t.strings[0]) + "'");
    mesh_.creaseMethod = t.strings[0] == "chaikin" ? CreaseMethod::Chaikin : CreaseMethod::Normal;
    return Status::ok();
}

// Zero-area polygons not sewn into the surface go (mesh_clean.h): their triangles,
// polygon ranges after them shifting down. Before the tags name triangles.
Status ObjParser::settleZeroArea() {
    const std::vector<size_t> dropped = cleaner_.settleZeroArea(mesh_, zeroArea_);
    if (!dropped.empty() && options_.cleaning == InputCleaning::Refuse)
        return failAt(zeroArea_[dropped[0]].tag, "face " + cleaner_.defect(FaceCleaner::Fate::ZeroArea, lineName));
    std::vector<uint8_t> drop(mesh_.faceCount(), 0);
    for (size_t i : dropped) std::fill_n(drop.begin() + zeroArea_[i].first, zeroArea_[i].count, 1);
    if (!dropped.empty()) eraseTriangles(mesh_, drop);
    uint32_t removed = 0;  // triangles before the polygon's first
    for (size_t p = 0, i = 0; p < polygons_.size(); ++p) {
        const uint32_t first = polyFirstTri_[p] - removed, count = polyFirstTri_[p + 1] - polyFirstTri_[p];
        if (polygons_[p].fate == uint8_t(FaceCleaner::Fate::ZeroArea)) {
            const bool gone = drop[polyFirstTri_[p]];
            const bool repaired = zeroArea_[i++].repaired;
            polygons_[p].fate = uint8_t(gone       ? FaceCleaner::Fate::ZeroArea
                                        : repaired ? FaceCleaner::Fate::Repaired
                                                   : FaceCleaner::Fate::Kept);
            if (gone) removed += count;
        }
        polyFirstTri_[p] = first;
    }
    polyFirstTri_.back() = uint32_t(mesh_.faceCount());
    return Status::ok();
}

void ObjParser::finishUVs() {
    size_t withUV = 0, withoutUV = 0;  // polygons kept
    for (size_t p = 0; p < polygons_.size(); ++p)
        if (polyFirstTri_[p + 1] != polyFirstTri_[p]) (polygons_[p].uv ? withUV : withoutUV)++;
    if (withUV != 0 && withoutUV != 0)
        warn(std::to_string(withoutUV) + " of " + std::to_string(withUV + withoutUV) +
             " faces have no texture coordinates; dropping all texture coordinates");
    if (withoutUV != 0) mesh_.faceUVs.clear();
}

Status ObjParser::statement(std::string_view line) {
    Tokens tokens(line.substr(0, line.find('#')));
    std::string_view kw;
    if (!tokens.next(kw)) return Status::ok();
    if (kw == "v") return vertex(tokens);
    if (kw == "vt") return texcoord(tokens);
    if (kw == "f") return face(tokens);
    if (kw == "t") return tag(tokens);
    if (kw == "vn" || kw == "o" || kw == "g" || kw == "s" || kw == "usemtl" || kw == "mtllib") return Status::ok();
    warnUnknown("statement", kw);
    return Status::ok();
}

Status ObjParser::run(std::string_view text) {
    mesh_ = InputMesh{};
    size_t pos = 0;
    while (pos < text.size()) {
        size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        ++line_;
        if (Status st = statement(text.substr(pos, end - pos)); !st) return st;
        pos = end + 1;
    }
    triangulate();
    if (Status st = settleZeroArea(); !st) return st;
    for (const Tag& t : tags_)
        if (Status st = applyTag(t); !st) return st;
    if (options_.boundary) {  // overrides the tag, which warns when it says otherwise
        if (boundaryTag_ && mesh_.boundary != *options_.boundary)
            warn("line " + std::to_string(boundaryTag_) + ": 'interpolateboundary' tag says " +
                 boundaryOptionName(mesh_.boundary) + "; using --boundary " + boundaryOptionName(*options_.boundary));
        mesh_.boundary = *options_.boundary;
    }
    keepPolygonCorners(polygonCorners_, mesh_);  // edge-and-corner on the polygons as written
    finishUVs();
    size_t split = 0, firstSplit = 0;
    for (size_t p = 0; p < polygons_.size(); ++p)
        if (polyFirstTri_[p + 1] - polyFirstTri_[p] > 1 && split++ == 0) firstSplit = polygons_[p].line;
    if (split != 0)
        warn(std::to_string(split) + " polygons with more than 3 sides were triangulated (first at line " +
             std::to_string(firstSplit) + ")");
    cleaner_.warn(name_, "polygon", lineName, mesh_.warnings);
    mesh_.cleaning = cleaner_.report();
    if (!removedEdges_.empty()) dropCreasesOfRemovedEdges(mesh_, removedEdges_, name_);
    return Status::ok();
}

}  // namespace

Status parseObj(std::string_view text, const std::string& name, const InputOptions& options, InputMesh& mesh) {
    try {
        Status st = ObjParser(name, options, mesh).run(text);
        if (!st) mesh = InputMesh{};
        return st;
    } catch (const std::exception& e) {  // bad_alloc, in practice
        mesh = InputMesh{};
        return Status::error(Status::Internal, name + ": " + e.what());
    }
}

}  // namespace lt
