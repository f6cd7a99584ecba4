// Level-of-detail test helpers (see lod_check.h).
#include "lod_check.h"
#include "test_paths.h"
#include "sanitizer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <unordered_map>

namespace lt::test {

std::vector<std::string> closedLodMeshes() {
    std::string corpus = corpusDir();
    std::vector<std::string> out = {corpus + "/meshes/spot.obj", corpus + "/opensubdiv-loop/loop_icosahedron.obj",
                                    corpus + "/opensubdiv-loop/loop_icos_semisharp.obj",
                                    corpus + "/opensubdiv-loop/loop_cubes_semisharp.obj",
                                    corpus + "/opensubdiv-loop/loop_tetrahedron.obj"};
    if (!kAsan) out.push_back(corpus + "/meshes/bob.obj");  // under ASan spot is the real mesh
    return out;
}

bool controlMeshIsClosed(const Asset& asset) {
    std::map<std::pair<uint32_t, uint32_t>, int> count;
    for (size_t f = 0; f < asset.faces.size(); ++f) {
        uint32_t a = asset.faces[f], b = asset.faces[f - f % 3 + (f + 1) % 3];
        ++count[{std::min(a, b), std::max(a, b)}];
    }
    return std::all_of(count.begin(), count.end(), [](const auto& e) { return e.second == 2; });
}

EvalSettings lodSettings(const Asset& asset, LodMode mode, int camera, float pixelsPerEdge) {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < asset.positions.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], asset.positions[i]);
        hi[i % 3] = std::max(hi[i % 3], asset.positions[i]);
    }
    const float dirs[2][3] = {{0.3f, 0.2f, 1.0f}, {-1.0f, 0.5f, -0.4f}};
    const float distance[2] = {1.6f, 4.0f};
    const float* d = dirs[camera];
    float len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    float radius = 0.5f * std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                    (hi[2] - lo[2]) * (hi[2] - lo[2]));
    float eye[3];
    for (int k = 0; k < 3; ++k) eye[k] = 0.5f * (lo[k] + hi[k]) + d[k] / len * distance[camera] * radius;
    EvalSettings es;
    es.lod = cameraLod(mode, eye, 40.0f, 512, pixelsPerEdge);
    return es;
}

EvalSettings lodForFactor(const Asset& asset, LodMode mode, int camera, float factor) {
    // F is proportional to 1 / pixelsPerEdge where lodTessFactor does not clamp it
    // to [1, 2^maxDepth]: find such a probe, then scale.
    float top = std::ldexp(1.0f, int(asset.maxDepth()));
    for (float probe = 1.0f / 64; probe < 1e6f; probe *= 2) {
        EvalSettings es = lodSettings(asset, mode, camera, probe);
        float f = lodTessFactor(asset, asset.positions.data(), es);
        if (f > 1.0f && f < top) {
            es.lod.pixelsPerEdge = probe * f / factor;
            return es;
        }
    }
    ADD_FAILURE() << "no unclamped probe";
    return EvalSettings{};
}

std::string WeldReport::summary() const {
    std::ostringstream s;
    s << vertices << " vertices welded into " << welded << ", " << edges << " edges, " << unmatchedEdges
      << " not shared by exactly two triangles (and " << sliverEdges << " slivers), " << degenerate
      << " degenerate triangles, largest merge " << largestMerge << " of the diagonal";
    return s.str();
}

WeldReport weldAndCountEdges(const Tessellation& soup, double diagonal) {
    WeldReport r;
    r.vertices = soup.vertexCount();
    const double eps = 2.5e-7 * diagonal;
    struct CellHash {
        size_t operator()(const std::array<int64_t, 3>& c) const {
            return size_t(c[0] * 73856093) ^ size_t(c[1] * 19349663) ^ size_t(c[2] * 83492791);
        }
    };
    // Union-find over all pairs closer than eps (transitively), so a sliver collapses
    // the same way whichever side of an edge it lies on.
    std::vector<uint32_t> parent(r.vertices);
    auto root = [&](uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    std::unordered_map<std::array<int64_t, 3>, std::vector<uint32_t>, CellHash> grid;
    const float* p = soup.positions.data();
    for (size_t v = 0; v < r.vertices; ++v) {
        parent[v] = uint32_t(v);
        std::array<int64_t, 3> cell;
        for (int k = 0; k < 3; ++k) cell[k] = int64_t(std::floor(double(p[3 * v + k]) / eps));
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    auto it = grid.find({cell[0] + dx, cell[1] + dy, cell[2] + dz});
                    if (it == grid.end()) continue;
                    for (uint32_t w : it->second) {
                        double d2 = 0;
                        for (int k = 0; k < 3; ++k) {
                            double e = double(p[3 * v + k]) - double(p[3 * size_t(w) + k]);
                            d2 += e * e;
                        }
                        if (std::sqrt(d2) > eps) continue;
                        r.largestMerge = std::max(r.largestMerge, std::sqrt(d2) / diagonal);
                        parent[root(uint32_t(v))] = root(w);
                    }
                }
        grid[cell].push_back(uint32_t(v));
    }
    std::vector<uint32_t> id(r.vertices);
    for (size_t v = 0; v < r.vertices; ++v) {
        id[v] = root(uint32_t(v));
        r.welded += id[v] == v;
    }
    std::unordered_map<uint64_t, uint32_t> edgeCount;
    for (size_t t = 0; t < soup.triangleCount(); ++t) {
        uint32_t c[3] = {id[3 * t], id[3 * t + 1], id[3 * t + 2]};
        if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) {
            ++r.degenerate;
            continue;
        }
        for (int e = 0; e < 3; ++e) {
            uint32_t a = c[e], b = c[(e + 1) % 3];
            ++edgeCount[uint64_t(std::min(a, b)) << 32 | std::max(a, b)];
        }
    }
    r.edges = edgeCount.size();
    for (const auto& e : edgeCount) {
        if (e.second == 2) continue;
        uint32_t a = uint32_t(e.first >> 32), b = uint32_t(e.first);
        double d2 = 0;
        for (int k = 0; k < 3; ++k) d2 += (double(p[3 * a + k]) - p[3 * b + k]) * (double(p[3 * a + k]) - p[3 * b + k]);
        ++(std::sqrt(d2) < 4 * eps ? r.sliverEdges : r.unmatchedEdges);
    }
    return r;
}

std::array<float, 7> ippKey(const PatchParam& param) {
    static const float corner[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    float d = std::ldexp(1.0f, -int(param.level)), sign = param.rotated ? -1.0f : 1.0f;
    std::array<float, 7> key{float(param.baseFace)};
    for (int c = 0; c < 3; ++c) {
        key[1 + 2 * c] = d * (float(param.ui) + sign * corner[c][0]);
        key[2 + 2 * c] = d * (float(param.vi) + sign * corner[c][1]);
    }
    return key;
}

std::array<float, 7> triangleKey(const Tessellation& soup, size_t t) {
    std::array<float, 7> key{float(soup.face[3 * t])};
    for (int c = 0; c < 6; ++c) key[1 + c] = soup.uv[6 * t + c];
    return key;
}

}  // namespace lt::test
