// A tessellation by base face and (u, v): the reference's gives a coarser
// tessellation's triangles their bound from the surface, and both map a ray's hit to
// its (face, u, v) and back (check_internal.h, SurfaceIndex).
//
// Each base face's (u, v) square is cut into grid x grid cells; a reference triangle
// is listed in the cell of its (u, v) box's low corner, and boxes span at most
// `reach` cells, so the triangles meeting a box of cells x0..x1, y0..y1 are listed in
// cells x0 - reach .. x1, y0 - reach .. y1:
//
//     v                                 the cell of (u, v):
//     1 +----+----+----+                  x = clamp(floor(u grid), 0, grid - 1)
//       |\   |    |    |                  y = clamp(floor(v grid), 0, grid - 1)
//       |  \ |    |    |                one list per (face, y, x), faces in order
//       +----\----+----+
//       |    | \  |    |                only u + v <= 1 holds triangles; the
//       |    |   \|    |                other half of the square stays empty
//       +----+----\----+
//       |    |    | \  |
//       |    |    |   \|
//     0 +----+----+----+ u
//       0              1
#include "check_internal.h"

#include <algorithm>
#include <cmath>

namespace lt {
namespace {

// Barycentrics in a (u, v) triangle q0 q1 q2 as an affine map: b1, b2 from x - q0.
struct Barycentric {
    double o[2] = {0, 0}, r[2][2] = {{0, 0}, {0, 0}};
    // False when the triangle has no area.
    bool set(const double q[6]) {
        const double e1[2] = {q[2] - q[0], q[3] - q[1]}, e2[2] = {q[4] - q[0], q[5] - q[1]};
        const double area2 = e1[0] * e2[1] - e1[1] * e2[0];
        if (!(area2 != 0)) return false;
        o[0] = q[0], o[1] = q[1];
        r[0][0] = e2[1] / area2, r[0][1] = -e2[0] / area2;
        r[1][0] = -e1[1] / area2, r[1][1] = e1[0] / area2;
        return true;
    }
    void at(const double x[2], double b[3]) const {
        const double d[2] = {x[0] - o[0], x[1] - o[1]};
        b[1] = r[0][0] * d[0] + r[0][1] * d[1];
        b[2] = r[1][0] * d[0] + r[1][1] * d[1];
        b[0] = 1.0 - b[1] - b[2];
    }
};

// A piece of a reference triangle inside the tested one: a convex polygon whose
// corners carry their barycentrics in both (g: the reference's, b: the tested one's),
// both affine, so a cut interpolates them. A triangle cut by three lines has at most
// 6 corners (one more, which only rounding could make, is dropped).
struct Piece {
    double g[6][3], b[6][3];
    int n = 0;
    void add(const double* gx, const double* bx) {
        if (n == 6) return;
        std::copy_n(gx, 3, g[n]), std::copy_n(bx, 3, b[n]), ++n;
    }
};

// `in` cut to where the tested triangle's barycentric k is >= 0.
Piece cut(const Piece& in, int k) {
    Piece out;
    for (int i = 0; i < in.n; ++i) {
        const int j = (i + 1) % in.n;
        const double wi = in.b[i][k], wj = in.b[j][k];
        if (wi >= 0) out.add(in.g[i], in.b[i]);
        if ((wi < 0 && wj > 0) || (wi > 0 && wj < 0)) {
            const double s = wi / (wi - wj);
            double g[3], b[3];
            for (int c = 0; c < 3; ++c)
                g[c] = in.g[i][c] + s * (in.g[j][c] - in.g[i][c]), b[c] = in.b[i][c] + s * (in.b[j][c] - in.b[i][c]);
            b[k] = 0;
            out.add(g, b);
        }
    }
    return out;
}

int cellOf(double x, uint32_t grid) { return std::clamp(int(std::floor(x * grid)), 0, int(grid) - 1); }

bool finite(const double* x, int n) {
    return std::all_of(x, x + n, [](double v) { return std::isfinite(v); });
}

}  // namespace

void SurfaceIndex::build(const Tessellation& soup, std::shared_ptr<const WeldedMesh> mesh) {
    mesh_ = std::move(mesh);
    const WeldedMesh& m = *mesh_;
    const size_t n = m.triangleCount();
    face_.resize(n);
    uv_.resize(6 * n);
    uint32_t faces = 0;
    for (size_t t = 0; t < n; ++t) {
        const size_t s = m.soupTriangle[t];
        face_[t] = soup.face[3 * s];
        faces = std::max(faces, face_[t] + 1);
        std::copy_n(&soup.uv[6 * s], 6, &uv_[6 * t]);
    }
    faceChord_.assign(faces, 0.0f);
    for (size_t t = 0; t < n; ++t) faceChord_[face_[t]] = std::max(faceChord_[face_[t]], m.chordBound[t]);
    // Cells about as large as the largest triangle's (u, v) box, so a box spans at most
    // `reach_` = 1 cell boundary; each triangle's cell (none when its (u, v) are not finite).
    double extent = 0;
    for (size_t t = 0; t < n; ++t) {
        double q[6];
        if (triangleUv(uint32_t(t), q))
            extent = std::max({extent, std::max({q[0], q[2], q[4]}) - std::min({q[0], q[2], q[4]}),
                               std::max({q[1], q[3], q[5]}) - std::min({q[1], q[3], q[5]})});
    }
    grid_ = uint32_t(std::clamp(extent > 0 ? std::floor(1.0 / extent) : 1.0, 1.0, 64.0));
    reach_ = int(std::min<double>(grid_, std::ceil(extent * grid_)));
    std::vector<uint32_t> cell(n, ~0u);
    for (size_t t = 0; t < n; ++t) {
        double q[6];
        if (!triangleUv(uint32_t(t), q)) continue;
        const double lo[2] = {std::min({q[0], q[2], q[4]}), std::min({q[1], q[3], q[5]})};
        cell[t] =
            uint32_t((size_t(face_[t]) * grid_ + size_t(cellOf(lo[1], grid_))) * grid_ + size_t(cellOf(lo[0], grid_)));
    }
    // Counting sort by cell: counts, prefix sums, then the lists.
    const size_t cells = size_t(faces) * grid_ * grid_;
    cellStart_.assign(cells + 1, 0);
    for (size_t t = 0; t < n; ++t)
        if (cell[t] != ~0u) ++cellStart_[cell[t] + 1];
    for (size_t c = 0; c < cells; ++c) cellStart_[c + 1] += cellStart_[c];
    listed_.assign(cellStart_[cells], 0);
    std::vector<uint32_t> next(cellStart_.begin(), cellStart_.end() - 1);
    for (size_t t = 0; t < n; ++t)
        if (cell[t] != ~0u) listed_[next[cell[t]]++] = uint32_t(t);
}

// The (u, v) of mesh triangle t's corners; false when not finite.
bool SurfaceIndex::triangleUv(uint32_t t, double q[6]) const {
    std::copy_n(&uv_[6 * size_t(t)], 6, q);
    return finite(q, 6);
}

// Calls visit(t) for every listed triangle whose (u, v) box may meet [lo, hi] on `face`.
template <class Visit>
void SurfaceIndex::forEachNear(uint32_t face, const double lo[2], const double hi[2], Visit&& visit) const {
    const int x0 = std::max(0, cellOf(lo[0], grid_) - reach_), x1 = cellOf(hi[0], grid_);
    const int y0 = std::max(0, cellOf(lo[1], grid_) - reach_), y1 = cellOf(hi[1], grid_);
    for (int y = y0; y <= y1; ++y) {
        const size_t row = (size_t(face) * grid_ + size_t(y)) * grid_;
        for (uint32_t i = cellStart_[row + size_t(x0)]; i < cellStart_[row + size_t(x1) + 1]; ++i) visit(listed_[i]);
    }
}

// The mesh's position at barycentrics g of its triangle t.
void SurfaceIndex::interpolate(uint32_t t, const double g[3], double p[3]) const {
    const uint32_t* v = &mesh_->triangles[3 * size_t(t)];
    for (int a = 0; a < 3; ++a) {
        p[a] = 0;
        for (int k = 0; k < 3; ++k) p[a] += g[k] * double(mesh_->positions[3 * size_t(v[k]) + size_t(a)]);
    }
}

bool SurfaceIndex::parameters(uint32_t t, double b1, double b2, uint32_t& face, double uv[2]) const {
    double q[6];
    if (!mesh_ || t >= face_.size() || !triangleUv(t, q)) return false;
    face = face_[t];
    for (int c = 0; c < 2; ++c) uv[c] = (1.0 - b1 - b2) * q[c] + b1 * q[2 + c] + b2 * q[4 + c];
    return finite(uv, 2);
}

bool SurfaceIndex::pointAt(uint32_t face, const double uv[2], uint32_t& triangle, double p[3]) const {
    if (!mesh_ || face >= faceChord_.size() || !finite(uv, 2)) return false;
    double best = -1e-7;  // how far outside a triangle (in barycentrics) still counts as in it
    bool found = false;
    forEachNear(face, uv, uv, [&](uint32_t t) {
        if (best >= 0) return;  // inside one: a neighbour sharing the point gives the same
        double q[6], g[3];
        triangleUv(t, q);  // finite: only those are listed
        Barycentric in;
        if (!in.set(q)) return;
        in.at(uv, g);
        const double worst = std::min({g[0], g[1], g[2]});
        if (!(worst >= best)) return;
        best = worst;
        found = true;
        triangle = t;
        interpolate(t, g, p);
    });
    return found;
}

bool SurfaceIndex::normalAt(uint32_t face, const double uv[2], double g[3]) const {
    uint32_t t = 0;
    double p[3];
    if (!pointAt(face, uv, t, p)) return false;
    const WeldedMesh& m = *mesh_;
    const float* c[3];
    for (int k = 0; k < 3; ++k) c[k] = &m.positions[3 * size_t(m.triangles[3 * size_t(t) + size_t(k)])];
    const double a[3] = {double(c[1][0]) - c[0][0], double(c[1][1]) - c[0][1], double(c[1][2]) - c[0][2]};
    const double b[3] = {double(c[2][0]) - c[0][0], double(c[2][1]) - c[0][1], double(c[2][2]) - c[0][2]};
    g[0] = a[1] * b[2] - a[2] * b[1];
    g[1] = a[2] * b[0] - a[0] * b[2];
    g[2] = a[0] * b[1] - a[1] * b[0];
    return true;
}

double SurfaceIndex::bound(const Tessellation& soup, size_t t) const {
    const uint32_t face = soup.face[3 * t];
    if (!mesh_ || face >= faceChord_.size() || soup.face[3 * t + 1] != face || soup.face[3 * t + 2] != face) return 0;
    double corner[6], at[3][3];
    std::copy_n(&soup.uv[6 * t], 6, corner);
    Barycentric tested;
    if (!finite(corner, 6) || !tested.set(corner)) return 0;
    uint32_t any = 0;
    for (int k = 0; k < 3; ++k)
        if (!pointAt(face, &corner[2 * k], any, at[k])) return 0;
    const double lo[2] = {std::min({corner[0], corner[2], corner[4]}), std::min({corner[1], corner[3], corner[5]})};
    const double hi[2] = {std::max({corner[0], corner[2], corner[4]}), std::max({corner[1], corner[3], corner[5]})};
    double d2 = 0;
    forEachNear(face, lo, hi, [&](uint32_t r) {
        Piece piece;
        piece.n = 3;
        bool outside[3] = {true, true, true}, cross[3] = {false, false, false};
        double q[6];
        triangleUv(r, q);
        for (int k = 0; k < 3; ++k) {
            tested.at(&q[2 * k], piece.b[k]);
            for (int c = 0; c < 3; ++c) {
                piece.g[k][c] = c == k ? 1.0 : 0.0;
                outside[c] = outside[c] && piece.b[k][c] < 0;
                cross[c] = cross[c] || piece.b[k][c] < 0;
            }
        }
        if (outside[0] || outside[1] || outside[2]) return;  // beyond one edge of the tested triangle
        for (int c = 0; c < 3 && piece.n > 0; ++c)
            if (cross[c]) piece = cut(piece, c);
        // R - sum b_k R(c_k) at the piece's corners.
        for (int j = 0; j < piece.n; ++j) {
            double onR[3], e2 = 0;
            interpolate(r, piece.g[j], onR);
            for (int a = 0; a < 3; ++a) {
                const double e =
                    onR[a] - (piece.b[j][0] * at[0][a] + piece.b[j][1] * at[1][a] + piece.b[j][2] * at[2][a]);
                e2 += e * e;
            }
            d2 = std::max(d2, e2);
        }
    });
    return std::sqrt(d2) + 2.0 * double(faceChord_[face]);
}

}  // namespace lt
