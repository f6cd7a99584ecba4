// bench/gen_mesh.cpp -- the generated torus and valence statistics (gen_mesh.h).
#include "gen_mesh.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace ltbench {
namespace {

// Knuth's MMIX LCG; next() returns a double in [0, 1) from the high 53 bits.
class Lcg {
public:
    explicit Lcg(uint64_t seed) : state_(seed) {}
    double next() {
        state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
        return double(state_ >> 11) * (1.0 / 9007199254740992.0);
    }

private:
    uint64_t state_;
};

}  // namespace

lt::InputMesh makeTorus(const TorusParams& p) {
    const uint32_t nu = std::max<uint32_t>(p.around, 3), nv = std::max<uint32_t>(p.across, 3);
    const double kPi = 3.14159265358979323846, kMajor = 1.0, kTube = 0.35;
    Lcg lcg(p.seed);
    auto id = [&](uint32_t i, uint32_t j) { return (i % nu) * nv + (j % nv); };

    lt::InputMesh mesh;
    mesh.faces.reserve(size_t(nu) * nv * 6);
    for (uint32_t i = 0; i < nu; ++i)
        for (uint32_t j = 0; j < nv; ++j) {
            // Cell corners: a, then b (+around), c (+both), d (+across): CCW from outside.
            const uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            const bool flip = p.flipOneIn > 0 && lcg.next() * p.flipOneIn < 1.0;
            const uint32_t tris[2][3] = {{a, b, flip ? d : c}, {flip ? b : a, c, d}};
            for (const auto& t : tris) mesh.faces.insert(mesh.faces.end(), t, t + 3);
        }
    mesh.positions.resize(size_t(nu) * nv * 3);
    for (uint32_t i = 0; i < nu; ++i)
        for (uint32_t j = 0; j < nv; ++j) {
            const double theta = 2 * kPi * i / nu, phi = 2 * kPi * j / nv;
            const double tube = kTube * (1.0 + p.noise * (lcg.next() - 0.5));
            const double ring = kMajor + tube * std::cos(phi);
            float* out = &mesh.positions[size_t(id(i, j)) * 3];
            out[0] = float(ring * std::cos(theta));
            out[1] = float(ring * std::sin(theta));
            out[2] = float(tube * std::sin(phi));
        }
    return mesh;
}

TorusParams scanParams() {
    TorusParams p;
    p.around = 1000;
    p.across = 500;
    p.flipOneIn = 2;
    return p;
}

bool generatedParams(const std::string& name, TorusParams& params) {
    if (name == "torus")
        params = TorusParams{};
    else if (name == "scan1m")
        params = scanParams();
    else
        return false;
    return true;
}

uint32_t countExtraordinary(const lt::InputMesh& mesh) {
    std::vector<std::pair<uint32_t, uint32_t>> edges;
    edges.reserve(mesh.faces.size());
    for (size_t f = 0; f + 2 < mesh.faces.size(); f += 3)
        for (int k = 0; k < 3; ++k) {
            uint32_t a = mesh.faces[f + k], b = mesh.faces[f + (k + 1) % 3];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    std::sort(edges.begin(), edges.end());
    std::vector<uint32_t> valence(mesh.vertexCount(), 0);
    std::vector<uint8_t> boundary(mesh.vertexCount(), 0);
    for (size_t i = 0; i < edges.size();) {
        size_t j = i;
        while (j < edges.size() && edges[j] == edges[i]) ++j;
        ++valence[edges[i].first];
        ++valence[edges[i].second];
        if (j - i == 1) boundary[edges[i].first] = boundary[edges[i].second] = 1;
        i = j;
    }
    uint32_t count = 0;
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v)
        if (valence[v] > 0 && valence[v] != (boundary[v] ? 4u : 6u)) ++count;
    return count;
}

}  // namespace ltbench
