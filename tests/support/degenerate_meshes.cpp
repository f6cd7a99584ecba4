// degenerateMesh (degenerate_meshes.h).
#include "degenerate_meshes.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

namespace lt::test {
namespace {

using Vec = std::array<double, 3>;

// Knuth's MMIX LCG; uniform doubles from its top 53 bits.
struct Random {
    uint64_t state;
    double uniform() {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return double(state >> 11) * 0x1p-53;
    }
    double between(double a, double b) { return a + (b - a) * uniform(); }
    int integer(int lo, int hi) { return lo + int(uniform() * double(hi - lo + 1)); }  // lo .. hi
    bool chance(double p) { return uniform() < p; }
};

constexpr double kTau = 6.283185307179586;

struct Mesh {
    std::vector<Vec> v;
    std::vector<std::array<int, 3>> f;
    std::vector<std::array<int, 2>> creases;
    int add(const Vec& p) {
        v.push_back(p);
        return int(v.size()) - 1;
    }
};

// A point at angle `a` on a ring of radius `r` round the z axis at height `z`.
Vec onRing(double a, double r, double z) { return {r * std::cos(a), r * std::sin(a), z}; }

// Ring points of a fan round `centre`: `count` angles spanning `span` from `start`,
// radii and heights waved by `bumps`; the fan (centre, ring_i, ring_i+1) winds
// counter-clockwise seen from +z (or from -z with `below`).
void fan(Mesh& m, Random& rnd, int centre, int faces, bool closed, double span, double start, double height,
         double bumps, bool below) {
    std::vector<int> ring;
    const int points = closed ? faces : faces + 1;
    for (int i = 0; i < points; ++i) {
        const double a = start + span * (double(i) + rnd.between(-0.2, 0.2) * (i > 0 && i + 1 < points)) /
                                     double(closed ? faces : faces);
        ring.push_back(m.add(onRing(a, 1.0 + bumps * rnd.between(-1, 1), height + bumps * rnd.between(-1, 1))));
    }
    for (int i = 0; i < faces; ++i) {
        const int a = ring[size_t(i)], b = ring[size_t((i + 1) % points)];
        m.f.push_back(below ? std::array<int, 3>{centre, b, a} : std::array<int, 3>{centre, a, b});
    }
}

void pinch(Mesh& m, Random& rnd) {
    const int c = m.add({0, 0, 0});
    const double wave = rnd.between(0.0, 0.6);
    fan(m, rnd, c, rnd.integer(3, 6), rnd.chance(0.7), kTau, 0, rnd.between(-0.3, 0.8), wave, false);
    fan(m, rnd, c, rnd.integer(3, 6), rnd.chance(0.7), kTau, rnd.uniform(), -rnd.between(-0.3, 0.8), wave, true);
}

void slit(Mesh& m, Random& rnd) {
    const int c = m.add({0, 0, rnd.between(-0.3, 0.5)});
    const int faces = rnd.integer(3, 7);  // two would be one triangle twice, wound both ways
    fan(m, rnd, c, faces, false, kTau, 0, 0.1, rnd.between(0.0, 0.3), false);
    // The last spoke's end onto the first's, or beside it.
    const Vec first = m.v[1];
    Vec& last = m.v.back();
    const double gap = rnd.chance(0.5) ? 0.0 : std::pow(10.0, -rnd.integer(3, 7));
    last = {first[0], first[1] + gap, first[2]};
    if (rnd.chance(0.5)) {  // an outer strip, cut open along the same spoke
        const int inner = int(m.v.size()) - (faces + 1);
        std::vector<int> outer;
        for (int i = 0; i < faces; ++i) {
            const Vec p = m.v[size_t(inner + i)];
            outer.push_back(m.add({2 * p[0], 2 * p[1], rnd.between(-0.3, 0.3)}));
        }
        const Vec o = m.v[size_t(outer[0])];
        outer.push_back(m.add({o[0], o[1] + gap, o[2]}));
        for (int i = 0; i < faces; ++i) {
            const int a = inner + i, b = inner + i + 1, oa = outer[size_t(i)], ob = outer[size_t(i) + 1];
            m.f.push_back({a, oa, ob});
            m.f.push_back({a, ob, b});
        }
    }
}

void corner(Mesh& m, Random& rnd) {
    const int c = m.add({0, 0, 0});
    const int faces = rnd.integer(4, 8);
    // Spokes 0, s1 and s2 sharp; the sector 0 .. s1 flat (z = 0) and wide.
    const int s1 = rnd.integer(2, faces - 2), s2 = rnd.integer(s1 + 1, faces - 1);
    const double wide = rnd.between(0.45, 0.85) * kTau;
    std::vector<int> ring;
    for (int i = 0; i < faces; ++i) {
        const double a = i <= s1 ? wide * i / s1 : wide + (kTau - wide) * (i - s1) / (faces - s1);
        const double z = i == 0 || i >= s1 ? (i == 0 || i == s1 ? 0.0 : rnd.between(-0.8, 0.8)) : 0.0;
        ring.push_back(m.add(onRing(a, rnd.between(0.4, 1.6), z)));
    }
    for (int i = 0; i < faces; ++i) m.f.push_back({c, ring[size_t(i)], ring[size_t((i + 1) % faces)]});
    for (int s : {0, s1, s2}) m.creases.push_back({c, ring[size_t(s)]});
}

void book(Mesh& m, Random& rnd) {
    const int a = m.add({0, 0, 0}), b = m.add({0, 0, 1});
    const int pages = rnd.integer(3, 4);
    for (int p = 0; p < pages; ++p) {
        const double angle = kTau * (p + rnd.between(-0.3, 0.3)) / pages;
        const int q = m.add(onRing(angle, rnd.between(0.5, 1.5), rnd.between(0.1, 0.9)));
        // Pages alternate their winding so each pair of neighbours agrees.
        m.f.push_back(p % 2 ? std::array<int, 3>{b, a, q} : std::array<int, 3>{a, b, q});
        if (rnd.chance(0.5)) {
            const int r = m.add(onRing(angle + rnd.between(-0.3, 0.3), rnd.between(0.5, 1.5), rnd.between(0.9, 1.6)));
            m.f.push_back(p % 2 ? std::array<int, 3>{q, r, b} : std::array<int, 3>{b, r, q});
        }
    }
}

void wideFan(Mesh& m, Random& rnd) {
    const int c = m.add({0, 0, rnd.between(-0.2, 0.4)});
    const int faces = rnd.integer(6, 10);
    fan(m, rnd, c, faces, false, rnd.between(0.5, 0.97) * kTau, 0, 0.0, rnd.between(0.0, 0.4), false);
    if (rnd.chance(0.5)) m.creases.push_back({c, c + 1 + rnd.integer(1, faces - 1)});
}

// A bumpy 5x5 grid, fan-triangulated, with a fin of 2..4 faces from one of its
// centre's neighbours round to another: the centre's edges to those two have three
// faces each, so it is a non-manifold vertex inside a non-manifold edge (a sheet
// vertex, spec "Sectors"), its grid split into two sheets of 1..5 faces.
//
//     .---n---.       the centre c and its six neighbours in the grid (e, ne,
//     |  /|  /|       n, w, sw, s, counter-clockwise); the fin runs c -> A -> q1
//     | / | / |       .. -> B over new points q above or below the grid, A and B
//     w---c---e       two of the six
//     | / | / |
//     |/  |/  |
//     sw--s---.
void sheets(Mesh& m, Random& rnd) {
    const double bump = rnd.between(0.0, 0.6);
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) {
            const double inner = i > 0 && i < 4 && j > 0 && j < 4 ? 0.25 : 0.0;
            m.add({i - 2 + inner * rnd.between(-1, 1), j - 2 + inner * rnd.between(-1, 1), bump * rnd.between(-1, 1)});
        }
    auto at = [](int i, int j) { return 5 * j + i; };
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            m.f.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            m.f.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    const int c = at(2, 2);
    const int ring[6] = {at(3, 2), at(3, 3), at(2, 3), at(1, 2), at(1, 1), at(2, 1)};
    const int a = rnd.integer(0, 5), b = (a + rnd.integer(1, 5)) % 6;
    const int faces = rnd.integer(2, 4);
    std::vector<int> spine = {ring[a]};
    for (int t = 1; t < faces; ++t) {
        const Vec& pa = m.v[size_t(ring[a])];
        const Vec& pb = m.v[size_t(ring[b])];
        const double s = double(t) / faces, up = rnd.chance(0.5) ? 1.0 : -1.0;
        spine.push_back(m.add({pa[0] + s * (pb[0] - pa[0]) + rnd.between(-0.5, 0.5),
                               pa[1] + s * (pb[1] - pa[1]) + rnd.between(-0.5, 0.5),
                               pa[2] + s * (pb[2] - pa[2]) + up * rnd.between(0.5, 1.5)}));
    }
    spine.push_back(ring[b]);
    const bool flip = rnd.chance(0.5);
    for (int t = 0; t < faces; ++t)
        m.f.push_back(flip ? std::array<int, 3>{c, spine[size_t(t) + 1], spine[size_t(t)]}
                           : std::array<int, 3>{c, spine[size_t(t)], spine[size_t(t) + 1]});
}

}  // namespace

DegenerateMesh degenerateMesh(uint64_t seed, uint32_t index) {
    static const char* const kKinds[] = {"pinch", "slit", "corner", "book", "wide_fan", "sheets"};
    Random rnd{seed ^ (0x9e3779b97f4a7c15ull * (uint64_t(index) + 1))};
    for (int i = 0; i < 4; ++i) rnd.uniform();
    Mesh m;
    const uint32_t kind = index % kDegenerateKinds;
    switch (kind) {
    case 0: pinch(m, rnd); break;
    case 1: slit(m, rnd); break;
    case 2: corner(m, rnd); break;
    case 3: book(m, rnd); break;
    case 4: wideFan(m, rnd); break;
    default: sheets(m, rnd); break;
    }
    // A random rotation (about a random axis), scale and offset.
    const double scale = std::pow(10.0, rnd.between(-2, 2)), turn = rnd.between(0, kTau);
    const double z = rnd.between(-1, 1), phi = rnd.between(0, kTau), s = std::sqrt(1 - z * z);
    const Vec k = {s * std::cos(phi), s * std::sin(phi), z};
    const Vec offset = {rnd.between(-10, 10) * scale, rnd.between(-10, 10) * scale, rnd.between(-10, 10) * scale};
    DegenerateMesh out;
    out.name = std::string(kKinds[kind]) + "_" + std::to_string(seed) + "_" + std::to_string(index);
    char line[128];
    for (const Vec& p : m.v) {  // Rodrigues' rotation
        const double c = std::cos(turn), sn = std::sin(turn), d = k[0] * p[0] + k[1] * p[1] + k[2] * p[2];
        const Vec x = {k[1] * p[2] - k[2] * p[1], k[2] * p[0] - k[0] * p[2], k[0] * p[1] - k[1] * p[0]};
        Vec q;
        for (int i = 0; i < 3; ++i)
            q[size_t(i)] =
                (p[size_t(i)] * c + x[size_t(i)] * sn + k[size_t(i)] * d * (1 - c)) * scale + offset[size_t(i)];
        std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", q[0], q[1], q[2]);
        out.obj += line;
    }
    for (const auto& f : m.f) {
        std::snprintf(line, sizeof line, "f %d %d %d\n", f[0] + 1, f[1] + 1, f[2] + 1);
        out.obj += line;
    }
    for (const auto& e : m.creases) {
        std::snprintf(line, sizeof line, "t crease 2/1/0 %d %d 10\n", e[0], e[1]);
        out.obj += line;
    }
    return out;
}

}  // namespace lt::test
