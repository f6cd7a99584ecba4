// Normals against the drawn triangles (check_internal.h, checkNormals).
#include "check_internal.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <unordered_map>
#include <vector>
#include <cmath>
#include <cstdio>

namespace lt {
namespace {

double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

double angle(const double a[3], const double b[3]) {
    const double c = dot(a, b) / std::sqrt(dot(a, a) * dot(b, b));
    return std::acos(std::clamp(c, -1.0, 1.0));
}

constexpr double kRightAngle = 1.5707963267948966;
// The longest edge of a judged triangle is at most this many times its smallest
// altitude (check.h: the in-plane bend of a sliver's long edge turns it over).
constexpr double kMaxAspect = 10;

// A drawn edge: its endpoints' position bits, the smaller first.
struct EdgeKey {
    std::array<uint32_t, 6> bits;
    bool operator==(const EdgeKey& o) const { return bits == o.bits; }
};
struct EdgeHash {
    size_t operator()(const EdgeKey& k) const {
        uint64_t h = 0;
        for (uint32_t b : k.bits) h = (h ^ b) * 0x100000001B3ull;
        return size_t(h ^ (h >> 29));
    }
};

EdgeKey edgeKey(const Tessellation& soup, size_t a, size_t b) {
    std::array<uint32_t, 3> pa, pb;
    std::memcpy(pa.data(), &soup.positions[3 * a], 12);
    std::memcpy(pb.data(), &soup.positions[3 * b], 12);
    if (pb < pa) std::swap(pa, pb);
    return {{pa[0], pa[1], pa[2], pb[0], pb[1], pb[2]}};
}

void cross(const double a[3], const double b[3], double g[3]) {
    g[0] = a[1] * b[2] - a[2] * b[1];
    g[1] = a[2] * b[0] - a[0] * b[2];
    g[2] = a[0] * b[1] - a[1] * b[0];
}

// Of the triangles in `candidates`, marks in `folded` those the drawn surface turns
// over at: some triangle sharing one of their edges (bit-equal endpoints) has a
// geometric normal more than 90 degrees from theirs. One scan over the soup.
void findFolds(const Tessellation& soup, const std::vector<size_t>& candidates, std::vector<char>& folded) {
    std::unordered_map<EdgeKey, std::vector<size_t>, EdgeHash> edges;  // edge -> candidate slots
    for (size_t c = 0; c < candidates.size(); ++c)
        for (size_t k = 0; k < 3; ++k)
            edges[edgeKey(soup, 3 * candidates[c] + k, 3 * candidates[c] + (k + 1) % 3)].push_back(c);
    folded.assign(candidates.size(), 0);
    for (size_t t = 0; t < soup.triangleCount(); ++t)
        for (size_t k = 0; k < 3; ++k) {
            auto it = edges.find(edgeKey(soup, 3 * t + k, 3 * t + (k + 1) % 3));
            if (it == edges.end()) continue;
            double g[3], h[3];
            geometricNormal(soup, t, g);
            for (size_t c : it->second) {
                if (candidates[c] == t) continue;
                geometricNormal(soup, candidates[c], h);
                if (dot(g, h) < 0) folded[c] = 1;
            }
        }
}

}  // namespace

void geometricNormal(const Tessellation& soup, size_t t, double g[3]) {
    const float* p = &soup.positions[9 * t];
    const double a[3] = {double(p[3]) - p[0], double(p[4]) - p[1], double(p[5]) - p[2]};
    const double b[3] = {double(p[6]) - p[0], double(p[7]) - p[1], double(p[8]) - p[2]};
    cross(a, b, g);
}

void checkNormals(const Tessellation& soup, NormalResult& out, const SurfaceIndex* finer,
                  const std::function<bool(size_t vertex)>& confirmed) {
    out = NormalResult{};
    struct Failure {
        size_t triangle;
        int corner;
        bool zero;
    };
    std::vector<Failure> failures;  // in triangle order
    for (size_t t = 0; t < soup.triangleCount(); ++t) {
        double p[3][3], n[3][3];
        bool finite = true;
        for (int k = 0; k < 3; ++k)
            for (int i = 0; i < 3; ++i) {
                p[k][i] = soup.positions[9 * t + 3 * k + i];
                n[k][i] = soup.normals[9 * t + 3 * k + i];
                finite = finite && std::isfinite(p[k][i]);
            }
        if (!finite) continue;  // W5 says so
        bool zero = false;
        for (int k = 0; k < 3; ++k) {
            const double len2 = dot(n[k], n[k]);
            if (std::isfinite(len2) && len2 > 0.25) continue;
            zero = true;
            ++out.zero;
            failures.push_back({t, k, true});
        }
        if (zero) continue;
        double a[3], b[3], c[3], g[3];  // a = p1 - p0, b = p2 - p0, c = p2 - p1; g = a x b
        for (int i = 0; i < 3; ++i) a[i] = p[1][i] - p[0][i], b[i] = p[2][i] - p[0][i], c[i] = p[2][i] - p[1][i];
        cross(a, b, g);
        const double longest2 = std::max({dot(a, a), dot(b, b), dot(c, c)});
        const double area2 = std::sqrt(dot(g, g));  // twice the area
        if (!(area2 > 1e-6 * longest2)) {
            ++out.unjudged;
            continue;
        }
        const double spread = std::max({angle(n[0], n[1]), angle(n[1], n[2]), angle(n[2], n[0])});
        const double r = longest2 / area2;  // longest edge / smallest altitude
        if (r > kMaxAspect || 0.1 + 0.5 * spread * r >= kRightAngle) {
            ++out.unjudged;
            continue;
        }
        ++out.judged;
        for (int k = 0; k < 3; ++k)
            if (!(dot(n[k], g) > 0)) failures.push_back({t, k, false});
    }
    // A triangle the drawn surface turns over at is not judged either (counted as folded).
    std::vector<size_t> candidates;
    for (const Failure& f : failures)
        if (!f.zero && (candidates.empty() || candidates.back() != f.triangle)) candidates.push_back(f.triangle);
    std::vector<char> folded;
    if (!candidates.empty()) findFolds(soup, candidates, folded);
    for (size_t c = 0; c < candidates.size(); ++c) out.folded += folded[c];
    out.judged -= out.folded;
    // Behind the coarse triangle but in front of the finer surface under the point: the
    // coarse triangle's plane is what is off (NormalResult).
    auto refined = [&](size_t v) {
        const double uv[2] = {soup.uv[2 * v], soup.uv[2 * v + 1]},
                     n[3] = {soup.normals[3 * v], soup.normals[3 * v + 1], soup.normals[3 * v + 2]};
        double g[3];
        return finer && finer->normalAt(soup.face[v], uv, g) && dot(n, g) > 0;
    };
    size_t c = 0;
    for (const Failure& f : failures) {
        if (!f.zero) {
            while (candidates[c] != f.triangle) ++c;
            if (folded[c]) continue;
            const size_t v = 3 * f.triangle + size_t(f.corner);
            if (refined(v)) {
                ++out.refined;
                continue;
            }
            if (confirmed && confirmed(v)) {
                ++out.confirmed;
                continue;
            }
            ++out.against;
        }
        if (!out.firstFailure.empty()) continue;
        const size_t v = 3 * f.triangle + size_t(f.corner);
        const float* n = &soup.normals[3 * v];
        char text[200];
        if (f.zero) {
            std::snprintf(text, sizeof text, "vertex %zu, face %u (u, v) = (%.9g, %.9g): normal (%g, %g, %g)", v,
                          soup.face[v], soup.uv[2 * v], soup.uv[2 * v + 1], n[0], n[1], n[2]);
        } else {
            double g[3], nd[3] = {n[0], n[1], n[2]};
            geometricNormal(soup, f.triangle, g);
            std::snprintf(text, sizeof text,
                          "vertex %zu, face %u (u, v) = (%.9g, %.9g): %.1f degrees from its triangle's normal", v,
                          soup.face[v], soup.uv[2 * v], soup.uv[2 * v + 1], angle(nd, g) * 90 / kRightAngle);
        }
        out.firstFailure = text;
    }
}

}  // namespace lt
