// Normals against the drawn triangles (check.h, checkNormals).
#include "looptess/check.h"

#include <algorithm>
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

} // namespace

void checkNormals(const Tessellation& soup, NormalResult& out) {
    out = NormalResult{};
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
            if (out.firstFailure.empty()) {
                const size_t v = 3 * t + size_t(k);
                char text[160];
                std::snprintf(text, sizeof text, "vertex %zu, face %u (u, v) = (%.9g, %.9g): normal (%g, %g, %g)", v,
                              soup.face[v], soup.uv[2 * v], soup.uv[2 * v + 1], n[k][0], n[k][1], n[k][2]);
                out.firstFailure = text;
            }
        }
        if (zero) continue;
        double a[3], b[3], c[3], g[3];  // a = p1 - p0, b = p2 - p0, c = p2 - p1; g = a x b
        for (int i = 0; i < 3; ++i) a[i] = p[1][i] - p[0][i], b[i] = p[2][i] - p[0][i], c[i] = p[2][i] - p[1][i];
        g[0] = a[1] * b[2] - a[2] * b[1];
        g[1] = a[2] * b[0] - a[0] * b[2];
        g[2] = a[0] * b[1] - a[1] * b[0];
        const double longest2 = std::max({dot(a, a), dot(b, b), dot(c, c)});
        const double area2 = std::sqrt(dot(g, g));  // twice the area
        if (!(area2 > 1e-6 * longest2)) {
            ++out.unjudged;
            continue;
        }
        const double spread = std::max({angle(n[0], n[1]), angle(n[1], n[2]), angle(n[2], n[0])});
        const double r = longest2 / area2;  // longest edge / smallest altitude
        if (0.1 + 0.5 * spread * r >= kRightAngle) {
            ++out.unjudged;
            continue;
        }
        ++out.judged;
        for (int k = 0; k < 3; ++k) {
            if (dot(n[k], g) > 0) continue;
            ++out.against;
            if (out.firstFailure.empty()) {
                const size_t v = 3 * t + size_t(k);
                char text[200];
                std::snprintf(text, sizeof text,
                              "vertex %zu, face %u (u, v) = (%.9g, %.9g): %.1f degrees from its triangle's normal",
                              v, soup.face[v], soup.uv[2 * v], soup.uv[2 * v + 1], angle(n[k], g) * 90 / kRightAngle);
                out.firstFailure = text;
            }
        }
    }
}

} // namespace lt
