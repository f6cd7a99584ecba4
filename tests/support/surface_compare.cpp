// A device's tessellation against the CPU evaluator's (surface_compare.h).
#include "surface_compare.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <array>
#include <vector>

namespace lt::test {
namespace {

// One vertex's attributes, read from a soup or through an indexed tessellation's
// indices (corner c of the triangle list).
struct Side {
    const Tessellation& t;
    size_t corners() const { return t.indices.empty() ? t.vertexCount() : t.indices.size(); }
    size_t vertex(size_t corner) const { return t.indices.empty() ? corner : t.indices[corner]; }
};

bool sameBits(const std::vector<float>& a, size_t i, const std::vector<float>& b, size_t j, size_t width) {
    if (a.empty() && b.empty()) return true;
    if (a.size() < (i + 1) * width || b.size() < (j + 1) * width) return false;
    for (size_t k = 0; k < width; ++k) {
        uint32_t x, y;
        std::memcpy(&x, &a[i * width + k], 4);
        std::memcpy(&y, &b[j * width + k], 4);
        if (x != y) return false;
    }
    return true;
}

enum : unsigned { kPosition = 1, kNormal = 2, kTangent = 4, kAttributes = 8 };

struct Measured {
    unsigned failed = 0;
    double position = 0, normal = 0, tangent = 0;
};

// Vertex i of `d` against vertex j of `c`.
Measured measure(const Tessellation& d, size_t i, const Tessellation& c, size_t j, const SurfaceMatch& m) {
    Measured r;
    for (int k = 0; k < 3; ++k) {
        const float a = d.positions[3 * i + k], b = c.positions[3 * j + k];
        if (std::memcmp(&a, &b, 4) == 0) continue;
        const double diff = std::isfinite(a) && std::isfinite(b) ? std::fabs(double(a) - double(b)) : INFINITY;
        r.position = std::max(r.position, diff);
        if (!(diff <= m.positionTolerance) || m.positionTolerance == 0) r.failed |= kPosition;
    }
    r.normal = angleBetween(&d.normals[3 * i], &c.normals[3 * j]);
    if (!(r.normal <= m.normalRadians)) r.failed |= kNormal;
    if (d.tangents.empty() != c.tangents.empty()) {
        r.failed |= kTangent;
    } else if (!d.tangents.empty()) {
        r.tangent = angleBetween(&d.tangents[4 * i], &c.tangents[4 * j]);
        if (!(r.tangent <= m.tangentRadians) || d.tangents[4 * i + 3] != c.tangents[4 * j + 3]) r.failed |= kTangent;
    }
    const bool attributes = d.face[i] == c.face[j] && sameBits(d.uv, i, c.uv, j, 2) &&
                            sameBits(d.texcoords, i, c.texcoords, j, 2) &&
                            sameBits(d.texcoords1, i, c.texcoords1, j, 2) && sameBits(d.colors, i, c.colors, j, 4);
    if (!attributes) r.failed |= kAttributes;
    return r;
}

std::string describe(unsigned failed) {
    std::string s;
    for (auto [bit, name] : {std::pair{kPosition, "position"},
                             {kNormal, "normal"},
                             {kTangent, "tangent"},
                             {kAttributes, "face, (u,v) or texture coordinates/colours"}})
        if (failed & bit) s += (s.empty() ? "" : ", ") + std::string(name);
    return s;
}

// `where` names the vertex (called only for the first difference).
template <class Where>
void record(SurfaceDiff& diff, const Measured& m, const Where& where) {
    diff.positions += (m.failed & kPosition) != 0;
    diff.normals += (m.failed & kNormal) != 0;
    diff.tangents += (m.failed & kTangent) != 0;
    diff.attributes += (m.failed & kAttributes) != 0;
    diff.worstPosition = std::max(diff.worstPosition, m.position);
    diff.worstNormal = std::max(diff.worstNormal, m.normal);
    diff.worstTangent = std::max(diff.worstTangent, m.tangent);
    if (m.failed && diff.first.empty()) diff.first = where() + ": " + describe(m.failed) + " differ";
}

// (base face, u bits, v bits): a domain point.
using Key = std::array<uint32_t, 3>;

Key keyOf(const Tessellation& t, size_t v) {
    Key k{t.face[v], 0, 0};
    std::memcpy(&k[1], &t.uv[2 * v], 4);
    std::memcpy(&k[2], &t.uv[2 * v + 1], 4);
    return k;
}

// Whether vertices i and j of `t` carry the same bits in every attribute.
bool sameVertex(const Tessellation& t, size_t i, size_t j) {
    return sameBits(t.positions, i, t.positions, j, 3) && sameBits(t.normals, i, t.normals, j, 3) &&
           sameBits(t.tangents, i, t.tangents, j, 4) && sameBits(t.texcoords, i, t.texcoords, j, 2) &&
           sameBits(t.texcoords1, i, t.texcoords1, j, 2) && sameBits(t.colors, i, t.colors, j, 4);
}

// Each domain point's vertices, one of each distinct set of attributes, sorted by key.
struct Point {
    Key key;
    size_t vertex;
    bool operator<(const Point& o) const { return key != o.key ? key < o.key : vertex < o.vertex; }
};
std::vector<Point> pointsOf(const Tessellation& t) {
    std::vector<Point> all;
    Side side{t};
    for (size_t corner = 0; corner < side.corners(); ++corner)
        all.push_back({keyOf(t, side.vertex(corner)), side.vertex(corner)});
    std::sort(all.begin(), all.end());
    std::vector<Point> points;
    size_t group = 0;  // first of the current key's points
    for (const Point& p : all) {
        if (!points.empty() && points[group].key != p.key) group = points.size();
        bool seen = false;
        for (size_t k = group; k < points.size() && !seen; ++k) seen = sameVertex(t, p.vertex, points[k].vertex);
        if (!seen) points.push_back(p);
    }
    return points;
}

// Every point of `from` against the points of `to` at its key: the best partner.
void matchPoints(const Tessellation& from, const std::vector<Point>& fromPoints, const Tessellation& to,
                 const std::vector<Point>& toPoints, const SurfaceMatch& m, bool fromDevice, SurfaceDiff& diff) {
    size_t j = 0;
    for (size_t i = 0; i < fromPoints.size();) {
        const Key key = fromPoints[i].key;
        size_t end = i;
        while (end < fromPoints.size() && fromPoints[end].key == key) ++end;
        while (j < toPoints.size() && toPoints[j].key < key) ++j;
        size_t toEnd = j;
        while (toEnd < toPoints.size() && toPoints[toEnd].key == key) ++toEnd;
        const size_t first = fromPoints[i].vertex;
        auto where = [&] {
            std::ostringstream s;
            s << (fromDevice ? "device" : "CPU") << " point at face " << key[0] << " (u,v) = (" << from.uv[2 * first]
              << ", " << from.uv[2 * first + 1] << ")";
            return s.str();
        };
        if (j == toEnd) {
            diff.unmatched += end - i;
            if (diff.first.empty()) diff.first = where() + ": no such point on the " + (fromDevice ? "CPU" : "device");
        }
        for (; i < end && j < toEnd; ++i) {
            const size_t v = fromPoints[i].vertex;
            Measured best;
            best.failed = ~0u;
            bool bitwise = false;  // a partner with the same normal bits
            for (size_t k = j; k < toEnd; ++k) {
                const size_t w = toPoints[k].vertex;
                Measured x = fromDevice ? measure(from, v, to, w, m) : measure(to, w, from, v, m);
                if (__builtin_popcount(x.failed) < __builtin_popcount(best.failed)) best = x;
                bitwise = bitwise || (x.failed == 0 && std::memcmp(&from.normals[3 * v], &to.normals[3 * w], 12) == 0);
            }
            record(diff, best, where);
            diff.normalsBitwise += fromDevice && bitwise;
        }
        i = end;
    }
}

}  // namespace

double angleBetween(const float* a, const float* b) {
    const double x[3] = {a[0], a[1], a[2]}, y[3] = {b[0], b[1], b[2]};
    const double c[3] = {x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
    const double cross = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    const double dot = x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    const bool zeroA = x[0] == 0 && x[1] == 0 && x[2] == 0, zeroB = y[0] == 0 && y[1] == 0 && y[2] == 0;
    if (zeroA || zeroB) return zeroA == zeroB ? 0.0 : M_PI;
    const double angle = std::atan2(cross, dot);
    return std::isfinite(angle) ? angle : M_PI;
}

Tessellation readPly(const std::string& bytes, bool& ok) {
    Tessellation t;
    ok = false;
    const size_t end = bytes.find("end_header\n");
    if (bytes.rfind("ply\nformat binary_little_endian 1.0\n", 0) != 0 || end == std::string::npos) return t;
    std::istringstream header(bytes.substr(0, end));
    std::string line;
    size_t vertices = 0, faces = 0;
    std::vector<std::string> names;  // the vertex properties, 4 bytes each
    while (std::getline(header, line)) {
        std::istringstream words(line);
        std::string word, type, name;
        words >> word;
        if (word == "element") {
            words >> type;
            (type == "vertex" ? vertices : faces) = std::stoul(line.substr(line.rfind(' ') + 1));
        } else if (word == "property" && faces == 0 && (words >> type >> name) && type != "list") {
            names.push_back(name);
        }
    }
    const char* body = bytes.data() + end + 11;
    if (bytes.size() != end + 11 + vertices * names.size() * 4 + faces * 13) return t;
    // Each attribute's properties in order and where they go.
    const std::pair<std::vector<const char*>, std::vector<float>*> attributes[] = {
        {{"x", "y", "z"}, &t.positions},
        {{"nx", "ny", "nz"}, &t.normals},
        {{"u", "v"}, &t.uv},
        {{"s", "t"}, &t.texcoords},
        {{"tx", "ty", "tz", "tw"}, &t.tangents},
        {{"s1", "t1"}, &t.texcoords1},
        {{"red", "green", "blue", "alpha"}, &t.colors}};
    auto column = [&](const char* name) {
        const auto it = std::find(names.begin(), names.end(), name);
        return it == names.end() ? SIZE_MAX : size_t(it - names.begin());
    };
    const size_t faceColumn = column("face");
    std::vector<std::pair<size_t, std::vector<float>*>> columns;  // (column, destination) in attribute order
    for (const auto& [props, out] : attributes)
        for (const char* name : props)
            if (const size_t c = column(name); c != SIZE_MAX) columns.push_back({c, out});
    for (const auto& [c, out] : columns) out->reserve(vertices * 4);
    for (size_t v = 0; v < vertices; ++v) {
        const char* at = body + v * names.size() * 4;
        for (const auto& [c, out] : columns) {
            float f;
            std::memcpy(&f, at + 4 * c, 4);
            out->push_back(f);
        }
        uint32_t face = 0;  // 0 where the file has none (vertexCount() counts faces)
        if (faceColumn != SIZE_MAX) std::memcpy(&face, at + 4 * faceColumn, 4);
        t.face.push_back(face);
    }
    bool soup = true;
    std::vector<uint32_t> indices;
    const char* list = body + vertices * names.size() * 4;
    for (size_t f = 0; f < faces; ++f) {
        if (list[13 * f] != 3) return t;
        uint32_t i[3];
        std::memcpy(i, list + 13 * f + 1, 12);
        for (int k = 0; k < 3; ++k) {
            if (i[k] >= vertices) return t;
            soup = soup && i[k] == 3 * f + k;
            indices.push_back(i[k]);
        }
    }
    if (!soup || vertices != 3 * faces) t.indices = std::move(indices);
    ok = true;
    return t;
}

std::string SurfaceDiff::summary() const {
    std::ostringstream s;
    s << vertices << " device vertices";
    if (!sameTriangleCount) s << ", a different number of triangles";
    s << "; unmatched " << unmatched << ", positions off " << positions << " (worst " << worstPosition
      << "), normals off " << normals << " (worst " << worstNormal << " rad, " << normalsBitwise
      << " bitwise), tangents off " << tangents << " (worst " << worstTangent << " rad), other attributes off "
      << attributes;
    if (!first.empty()) s << "; first: " << first;
    return s.str();
}

SurfaceDiff compareSurfaces(const Tessellation& device, const Tessellation& cpu, const SurfaceMatch& match) {
    SurfaceDiff diff;
    diff.sameTriangleCount = device.triangleCount() == cpu.triangleCount();
    Side d{device}, c{cpu};
    diff.vertices = d.corners();
    // In emission order first: where every vertex passes (one device's own order, as
    // lavapipe's is the CPU's), the sets of points are the same too.
    if (match.order == Order::Any && d.corners() == c.corners()) {
        SurfaceDiff inOrder = compareSurfaces(
            device, cpu,
            SurfaceMatch{Order::Emission, match.positionTolerance, match.normalRadians, match.tangentRadians});
        if (inOrder.ok()) return inOrder;
    }
    if (match.order == Order::Emission) {
        if (d.corners() != c.corners()) {
            diff.unmatched = std::max(d.corners(), c.corners()) - std::min(d.corners(), c.corners());
            diff.first = "different vertex counts";
        }
        for (size_t corner = 0; corner < std::min(d.corners(), c.corners()); ++corner) {
            const size_t i = d.vertex(corner), j = c.vertex(corner);
            Measured m = measure(device, i, cpu, j, match);
            record(diff, m, [&] {
                return "vertex " + std::to_string(corner) + " (triangle " + std::to_string(corner / 3) + ")";
            });
            diff.normalsBitwise += m.failed == 0 && std::memcmp(&device.normals[3 * i], &cpu.normals[3 * j], 12) == 0;
        }
        return diff;
    }
    const auto devicePoints = pointsOf(device), cpuPoints = pointsOf(cpu);
    matchPoints(device, devicePoints, cpu, cpuPoints, match, true, diff);
    SurfaceDiff back;  // every CPU point has a device partner too
    matchPoints(cpu, cpuPoints, device, devicePoints, match, false, back);
    diff.unmatched += back.unmatched + back.positions + back.normals + back.tangents + back.attributes;
    if (diff.first.empty()) diff.first = back.first;
    return diff;
}

}  // namespace lt::test
