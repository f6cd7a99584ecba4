// obj_tags.cpp -- the OBJ reader's OpenSubdiv tags (`t crease`, `corner`, `hole`,
// `interpolateboundary`, `creasemethod`, `vertexedit`; obj_reader.cpp's header has
// the grammar): each read and checked as its line comes, applied once every face is
// read and triangulated.
#include "obj_parser.h"
#include "resource_limits.h"
#include "text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace lt::obj {

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

}  // namespace lt::obj
