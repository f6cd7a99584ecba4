// obj_reader.cpp -- lt::parseObj: Wavefront OBJ text with OpenSubdiv's tags (the
// tags themselves: obj_tags.cpp; the parser both share: obj_parser.h).
//
// Grammar accepted (one statement per line, '#' starts a comment; a UTF-8 byte order
// mark at the start is skipped):
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
#include "looptess/tools/triangulate.h"
#include "obj_parser.h"
#include "resource_limits.h"
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

namespace lt::obj {
namespace {

constexpr size_t kMaxUnknownKeywords = 16;  // distinct keywords warned about

}  // namespace

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
    // A UTF-8 byte order mark (Windows editors write one) is not part of line 1:
    // read as text it made "v" an unknown statement, and every vertex after it one
    // index off.
    size_t pos = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
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

}  // namespace lt::obj

namespace lt {

Status parseObj(std::string_view text, const std::string& name, const InputOptions& options, InputMesh& mesh) {
    try {
        Status st = obj::ObjParser(name, options, mesh).run(text);
        if (!st) mesh = InputMesh{};
        return st;
    } catch (const std::exception& e) {  // bad_alloc, in practice
        mesh = InputMesh{};
        return Status::error(Status::Internal, name + ": " + e.what());
    }
}

}  // namespace lt
