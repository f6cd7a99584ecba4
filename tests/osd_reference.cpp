// OpenSubdiv oracle for the accuracy tests (see osd_reference.h).
#include "osd_reference.h"

#include "refine.h"  // the baker's refiner construction: the same topology and options

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace lt::test {
namespace {

struct Vec3 {
    double p[3] = {0, 0, 0};
    void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0; }
    void AddWithWeight(const Vec3& src, double w) {
        for (int k = 0; k < 3; ++k) p[k] += w * src.p[k];
    }
};

std::unique_ptr<Far::TopologyRefiner> refinerFor(const InputMesh& mesh, int depth) {
    std::unique_ptr<Far::TopologyRefiner> refiner;
    Status st = buildRefiner(mesh, depth, "oracle", refiner);
    EXPECT_TRUE(st) << st.message;
    return refiner;
}

// Every refined vertex of every level, in double, level after level.
std::vector<Vec3> refineAll(const Far::TopologyRefiner& refiner, const InputMesh& mesh) {
    std::vector<Vec3> all(size_t(refiner.GetNumVerticesTotal()));
    for (uint32_t v = 0; v < mesh.vertexCount(); ++v)
        for (int k = 0; k < 3; ++k) all[v].p[k] = mesh.positions[v * 3 + k];
    Far::PrimvarRefinerReal<double> primvar(refiner);
    Vec3* src = all.data();
    for (int l = 1; l <= refiner.GetMaxLevel(); ++l) {
        Vec3* dst = src + refiner.GetLevel(l - 1).GetNumVertices();
        primvar.Interpolate(l, src, dst);
        src = dst;
    }
    return all;
}

} // namespace

InputMesh loadObj(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    EXPECT_TRUE(in.good()) << "cannot open " << path;
    std::stringstream text;
    text << in.rdbuf();
    InputMesh mesh;
    std::string body = text.str();
    Status st = parseObj(body, path, InputOptions{}, mesh);
    EXPECT_TRUE(st) << st.message;
    return mesh;
}

std::vector<std::string> corpusShapes() {
    std::vector<std::string> shapes;
    for (const auto& e : std::filesystem::directory_iterator(std::string(LOOPTESS_CORPUS_DIR) + "/opensubdiv-loop"))
        if (e.path().extension() == ".obj") shapes.push_back(e.path().string());
    std::sort(shapes.begin(), shapes.end());
    return shapes;
}

std::string corpusMesh(const char* name) { return std::string(LOOPTESS_CORPUS_DIR) + "/meshes/" + name; }

double bboxDiagonal(const InputMesh& mesh) {
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], double(mesh.positions[i]));
        hi[i % 3] = std::max(hi[i % 3], double(mesh.positions[i]));
    }
    return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                     (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

struct OsdRefinement::Impl {
    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::vector<Vec3> vertices;
    std::vector<size_t> levelStart;
};

OsdRefinement::OsdRefinement(const InputMesh& mesh, int maxDepth) : impl_(new Impl) {
    impl_->refiner = refinerFor(mesh, maxDepth);
    if (!impl_->refiner) return;
    impl_->vertices = refineAll(*impl_->refiner, mesh);
    size_t start = 0;
    for (int l = 0; l <= impl_->refiner->GetMaxLevel(); ++l) {
        impl_->levelStart.push_back(start);
        start += size_t(impl_->refiner->GetLevel(l).GetNumVertices());
    }
}

OsdRefinement::~OsdRefinement() = default;

const double* OsdRefinement::vertex(int level, int vertex) const {
    return impl_->vertices[impl_->levelStart[size_t(level)] + size_t(vertex)].p;
}

int OsdRefinement::levels() const { return int(impl_->levelStart.size()); }

struct OsdLimit::Impl {
    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::unique_ptr<Far::PatchTable> patches;
    std::unique_ptr<Far::PatchMap> map;
    std::vector<Vec3> points;  // refined vertices, then the patch table's local points
};

OsdLimit::OsdLimit(const InputMesh& mesh, int isolation) : impl_(new Impl) {
    impl_->refiner = refinerFor(mesh, isolation);
    if (!impl_->refiner) return;
    Far::PatchTableFactory::Options options(isolation);
    options.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
    options.SetPatchPrecision<double>();
    options.useInfSharpPatch = true;
    impl_->patches.reset(Far::PatchTableFactory::Create(*impl_->refiner, options));
    impl_->map.reset(new Far::PatchMap(*impl_->patches));
    impl_->points = refineAll(*impl_->refiner, mesh);
    size_t refined = impl_->points.size();
    impl_->points.resize(refined + size_t(impl_->patches->GetNumLocalPoints()));
    if (auto* local = impl_->patches->GetLocalPointStencilTable<double>())
        local->UpdateValues(impl_->points.data(), impl_->points.data() + refined);
}

OsdLimit::~OsdLimit() = default;

bool OsdLimit::evaluate(int face, double u, double v, double pos[3], double normal[3]) const {
    const Far::PatchTable::PatchHandle* h = impl_->map->FindPatch(face, u, v);
    if (!h) return false;
    double w[20], wu[20], wv[20];
    impl_->patches->EvaluateBasis<double>(*h, u, v, w, wu, wv);
    auto cvs = impl_->patches->GetPatchVertices(*h);
    double du[3] = {0, 0, 0}, dv[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) pos[k] = 0;
    for (int i = 0; i < cvs.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            const double x = impl_->points[size_t(cvs[i])].p[k];
            pos[k] += w[i] * x;
            du[k] += wu[i] * x;
            dv[k] += wv[i] * x;
        }
    normal[0] = du[1] * dv[2] - du[2] * dv[1];
    normal[1] = du[2] * dv[0] - du[0] * dv[2];
    normal[2] = du[0] * dv[1] - du[1] * dv[0];
    double len = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    for (int k = 0; k < 3; ++k) normal[k] = len > 0 ? normal[k] / len : 0.0;
    return true;
}

bool OsdLimit::normalUndefined(int face, double u, double v) const {
    const Far::TopologyLevel& base = impl_->refiner->GetLevel(0);
    auto fv = base.GetFaceVertices(face);
    auto fe = base.GetFaceEdges(face);
    const double corner[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    for (int i = 0; i < 3; ++i) {
        if (u != corner[i][0] || v != corner[i][1]) continue;
        OsdIndex x = fv[i];
        if (base.IsVertexNonManifold(x)) return true;
        int sharp = 0;
        for (OsdIndex e : base.GetVertexEdges(x)) sharp += base.IsEdgeInfSharp(e) || base.IsEdgeBoundary(e);
        if (base.IsVertexInfSharp(x) && sharp < 2) return true;
    }
    bool onEdge[3] = {v == 0, u + v == 1, u == 0};
    for (int i = 0; i < 3; ++i)
        if (onEdge[i] && base.IsEdgeNonManifold(fe[i])) return true;
    return false;
}

} // namespace lt::test
