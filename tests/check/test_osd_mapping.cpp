// The two mappings of a mesh to OpenSubdiv's Far topology agree: the bridge the
// baker builds on (looptess/tools/osd.h, createRefiner) and the accuracy oracle's own
// (check/internal/osd_topology.h, oracleRefiner). They are written apart so that a
// mistake in one -- a crease dropped, a hole lost, the wrong boundary option --
// cannot sit on both sides of the accuracy checks; this shows they build the same
// level 0: Sdc options, vertices, faces, edges, edge and vertex sharpness, rules,
// holes. Meshes: the corpus (OpenSubdiv's Loop shapes with their creases, corners and
// boundary options; spot, bob, fandisk), the corner-normal meshes, and the real
// meshes read as loopbake reads them, as they are and with creases from
// --crease-angle 40, semi-sharp creases and corners, holes and the other options.
#include "looptess/tools/baker.h"
#include "looptess/tools/file_io.h"
#include "looptess/tools/osd.h"
#include "osd_reference.h"  // loadObj, corpusShapes, corpusMesh
#include "osd_topology.h"
#include "test_paths.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace lt::test {
namespace {

namespace fs = std::filesystem;

// Up to the first few differences between level 0 of `a` and of `b`, one a line
// ("edge 12 sharpness 10 / 0"); empty when they agree. Elements are compared by
// index: the same faces in the same order give Far's edges the same numbering.
class Differences {
public:
    Differences(const Far::TopologyRefiner& a, const Far::TopologyRefiner& b) {
        const Sdc::Options oa = a.GetSchemeOptions(), ob = b.GetSchemeOptions();
        same("scheme", -1, int(a.GetSchemeType()), int(b.GetSchemeType()));
        same("boundary interpolation", -1, oa.GetVtxBoundaryInterpolation(), ob.GetVtxBoundaryInterpolation());
        same("face-varying interpolation", -1, oa.GetFVarLinearInterpolation(), ob.GetFVarLinearInterpolation());
        same("crease method", -1, oa.GetCreasingMethod(), ob.GetCreasingMethod());
        same("triangle subdivision", -1, oa.GetTriangleSubdivision(), ob.GetTriangleSubdivision());
        same("face-varying channels", -1, a.GetNumFVarChannels(), b.GetNumFVarChannels());
        const Far::TopologyLevel &la = a.GetLevel(0), &lb = b.GetLevel(0);
        if (!same("vertices", -1, la.GetNumVertices(), lb.GetNumVertices()) ||
            !same("faces", -1, la.GetNumFaces(), lb.GetNumFaces()) ||
            !same("edges", -1, la.GetNumEdges(), lb.GetNumEdges()))
            return;
        for (OsdIndex f = 0; f < la.GetNumFaces(); ++f) {
            same("face hole", f, la.IsFaceHole(f), lb.IsFaceHole(f));
            sameArray("face vertices", f, la.GetFaceVertices(f), lb.GetFaceVertices(f));
        }
        for (OsdIndex e = 0; e < la.GetNumEdges(); ++e) {
            sameArray("edge vertices", e, la.GetEdgeVertices(e), lb.GetEdgeVertices(e));
            same("edge sharpness", e, la.GetEdgeSharpness(e), lb.GetEdgeSharpness(e));
            same("edge non-manifold", e, la.IsEdgeNonManifold(e), lb.IsEdgeNonManifold(e));
        }
        for (OsdIndex v = 0; v < la.GetNumVertices(); ++v) {
            same("vertex sharpness", v, la.GetVertexSharpness(v), lb.GetVertexSharpness(v));
            same("vertex rule", v, la.GetVertexRule(v), lb.GetVertexRule(v));
            same("vertex boundary", v, la.IsVertexBoundary(v), lb.IsVertexBoundary(v));
        }
    }
    size_t count() const { return count_; }
    std::string text() const { return text_.str(); }

private:
    template <typename T>
    bool same(const char* what, int index, T a, T b) {
        if (a == b) return true;
        if (count_++ < 8)
            text_ << what << (index >= 0 ? " " + std::to_string(index) : "") << ": " << a << " / " << b << "\n";
        return false;
    }
    template <typename A>
    void sameArray(const char* what, int index, const A& a, const A& b) {
        auto list = [](const A& x) {
            std::string s;
            for (int i = 0; i < x.size(); ++i) s += (i ? " " : "") + std::to_string(x[i]);
            return s;
        };
        same(what, index, list(a), list(b));
    }
    size_t count_ = 0;
    std::ostringstream text_;
};

// Whether both mappings refuse `mesh`, or both accept it with the same level 0;
// `accepted` counts the meshes both accept.
void expectAgreement(const InputMesh& mesh, const std::string& name, size_t& accepted) {
    SCOPED_TRACE(name);
    std::unique_ptr<Far::TopologyRefiner> bridge, oracle;
    const Status b = createRefiner(mesh, name, bridge), o = oracleRefiner(mesh, name, oracle);
    ASSERT_EQ(bool(b), bool(o)) << "bridge: " << b.message << "\noracle: " << o.message;
    if (!b) return;
    const Differences d(*bridge, *oracle);
    EXPECT_EQ(d.count(), 0u) << "bridge / oracle:\n" << d.text();
    ++accepted;
}

// Every feature at once: half of the creases semi-sharp, semi-sharp corners on
// every 13th vertex, every 9th face a hole, corners kept sharp on the boundary,
// Chaikin's crease rule.
InputMesh withFeatures(InputMesh mesh) {
    for (size_t i = 0; i < mesh.creases.size(); i += 2) mesh.creases[i].sharpness = 1.5f;
    for (uint32_t v = 0; v < mesh.vertexCount(); v += 13) mesh.corners.push_back({v, 2.5f});
    for (uint32_t f = 4; f < mesh.faceCount(); f += 9) mesh.holes.push_back(f);
    mesh.boundary = BoundaryInterpolation::EdgeAndCorner;
    mesh.creaseMethod = CreaseMethod::Chaikin;
    return mesh;
}

// A real mesh read as loopbake reads it (default options); fails the test if it
// cannot be read.
InputMesh readReal(const fs::path& path) {
    InputMesh mesh;
    std::vector<uint8_t> bytes;
    Status st = readFile(path.string(), bytes);
    if (st && path.extension() == ".obj")
        st = parseObj(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path.string(),
                      InputOptions{}, mesh);
    else if (st)
        st = parseGltf(bytes.data(), bytes.size(), path.string(), path.parent_path().string(), mesh);
    EXPECT_TRUE(st) << st.message;
    return mesh;
}

TEST(OsdMapping, CorpusAgrees) {
    std::vector<std::string> paths = corpusShapes();
    for (const char* name : {"spot.obj", "bob.obj", "fandisk.obj"}) paths.push_back(corpusMesh(name));
    for (const auto& e : fs::directory_iterator(testDataDir() + "/normals"))
        if (e.path().extension() == ".obj") paths.push_back(e.path().string());
    size_t accepted = 0;
    for (const std::string& path : paths) {
        const InputMesh mesh = loadObj(path);
        expectAgreement(mesh, path, accepted);
        expectAgreement(withFeatures(mesh), path + " (with features)", accepted);
    }
    EXPECT_EQ(accepted, 2 * paths.size());  // OpenSubdiv takes every one
    std::printf("[ figures  ] %zu of %zu corpus meshes and variants mapped alike\n", accepted, 2 * paths.size());
}

TEST(OsdMapping, RealMeshesAgree) {
    size_t accepted = 0, meshes = 0;
    for (const auto& e : fs::directory_iterator(testDataDir() + "/real")) {
        const std::string ext = e.path().extension().string();
        if (ext != ".obj" && ext != ".glb" && ext != ".gltf") continue;
        InputMesh mesh = readReal(e.path());
        expectAgreement(mesh, e.path().string(), accepted);
        addCreasesByAngle(mesh, 40);  // loopbake --crease-angle 40
        expectAgreement(mesh, e.path().string() + " (--crease-angle 40)", accepted);
        expectAgreement(withFeatures(mesh), e.path().string() + " (with features)", accepted);
        meshes += 3;
    }
    EXPECT_EQ(accepted, meshes);
    EXPECT_GE(meshes, size_t(3 * 17));
    std::printf("[ figures  ] %zu real meshes and variants mapped alike\n", accepted);
}

// The comparison sees what a mapping could drop: a mesh without one of its creases,
// corners or holes, or with another boundary or crease option, against the oracle's
// level 0 of the mesh itself.
TEST(OsdMapping, ComparisonSeesADroppedFeature) {
    const InputMesh mesh = withFeatures(loadObj(corpusShapes().front()));  // loop_chaikin0: 29 creases
    ASSERT_FALSE(mesh.creases.empty() || mesh.corners.empty() || mesh.holes.empty());
    std::unique_ptr<Far::TopologyRefiner> oracle;
    ASSERT_TRUE(oracleRefiner(mesh, "oracle", oracle));
    std::vector<std::pair<std::string, InputMesh>> planted(5, {"", mesh});
    planted[0].first = "a crease dropped";
    planted[0].second.creases.pop_back();
    planted[1].first = "a corner dropped";
    planted[1].second.corners.pop_back();
    planted[2].first = "a hole dropped";
    planted[2].second.holes.pop_back();
    planted[3].first = "boundary edge-only";
    planted[3].second.boundary = BoundaryInterpolation::EdgeOnly;
    planted[4].first = "crease method normal";
    planted[4].second.creaseMethod = CreaseMethod::Normal;
    for (const auto& [what, changed] : planted) {
        std::unique_ptr<Far::TopologyRefiner> bridge;
        ASSERT_TRUE(createRefiner(changed, what, bridge));
        EXPECT_GT(Differences(*bridge, *oracle).count(), 0u) << what;
    }
}

}  // namespace
}  // namespace lt::test
