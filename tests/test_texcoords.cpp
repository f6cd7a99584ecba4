// tests/test_texcoords.cpp -- TEXCOORD_0 on the limit surface (issue 15 item 3, CPU
// evaluation): every captured vertex's texcoord against OpenSubdiv's face-varying
// evaluation with FVAR_LINEAR_ALL at the same (face, u, v), through a Far::PatchTable
// with face-varying tables built here from the asset's control mesh and corner UVs.
// It pins the conventions too: which corner is (0,0), (1,0), (0,1) of a base face.
#include "looptess/asset.h"
#include "looptess/baker.h"
#include "looptess/runtime.h"

#include <gtest/gtest.h>

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <vector>

namespace {

using namespace OpenSubdiv;

std::vector<uint8_t> slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// OpenSubdiv's face-varying UVs of `asset`'s base faces: a Loop refiner isolated to
// level 0 (one patch per base face) with one channel, one value per face corner,
// FVAR_LINEAR_ALL, and linear face-varying patches.
class OsdTexcoords {
public:
    explicit OsdTexcoords(const lt::Asset& a) : values_(a.faceUVs) {
        std::vector<int> verts(a.faces.begin(), a.faces.end()), perFace(a.faceCount(), 3), corners(a.faces.size());
        for (size_t c = 0; c < corners.size(); ++c) corners[c] = int(c);
        Far::TopologyDescriptor desc;
        desc.numVertices = int(a.controlVertexCount());
        desc.numFaces = int(a.faceCount());
        desc.numVertsPerFace = perFace.data();
        desc.vertIndicesPerFace = verts.data();
        Far::TopologyDescriptor::FVarChannel channel;
        channel.numValues = int(corners.size());
        channel.valueIndices = corners.data();
        desc.numFVarChannels = 1;
        desc.fvarChannels = &channel;
        Sdc::Options sdc;
        sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
        sdc.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_ALL);
        using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
        refiner_.reset(Factory::Create(desc, Factory::Options(Sdc::SCHEME_LOOP, sdc)));
        Far::PatchTableFactory::Options options;
        options.generateFVarTables = true;
        options.generateFVarLegacyLinearPatches = true;
        options.SetPatchPrecision<double>();
        options.SetFVarPatchPrecision<double>();
        refiner_->RefineAdaptive(Far::TopologyRefiner::AdaptiveOptions(0));   // a patch per base face
        patches_.reset(Far::PatchTableFactory::Create(*refiner_, options));
        map_ = std::make_unique<Far::PatchMap>(*patches_);
    }

    bool evaluate(int face, double u, double v, double st[2]) const {
        const Far::PatchTable::PatchHandle* h = map_->FindPatch(face, u, v);
        if (!h) return false;
        double w[20];
        patches_->EvaluateBasisFaceVarying<double>(*h, u, v, w);
        const auto cvs = patches_->GetPatchFVarValues(*h);
        st[0] = st[1] = 0;
        for (int i = 0; i < cvs.size(); ++i)
            for (int k = 0; k < 2; ++k) st[k] += w[i] * double(values_[2 * size_t(cvs[i]) + size_t(k)]);
        return true;
    }

private:
    std::vector<float> values_;
    std::unique_ptr<Far::TopologyRefiner> refiner_;
    std::unique_ptr<Far::PatchTable> patches_;
    std::unique_ptr<Far::PatchMap> map_;
};

// The Duck's TEXCOORD_0 (4,212 faces, split at UV seams) baked from its glTF, read
// back as the format gives it, evaluated and compared.
TEST(Texcoords, EveryVertexMatchesOpenSubdivsLinearFaceVaryingValue) {
    const std::string file = std::string(LOOPTESS_CORPUS_DIR) + "/gltf/Duck.glb";
    const std::vector<uint8_t> bytes = slurp(file);
    lt::GltfScene scene;
    ASSERT_TRUE(lt::parseGltfScene(bytes.data(), bytes.size(), file, "", lt::Limits{}, scene));
    lt::BakeSettings settings;
    settings.maxDepth = 3;
    std::vector<lt::SceneSurface> surfaces(1);
    surfaces[0].mesh = scene.meshes[0].index;
    surfaces[0].primitives = scene.meshes[0].primitives;
    surfaces[0].controlVertex = scene.meshes[0].controlVertex;
    ASSERT_TRUE(lt::bake(scene.meshes[0].mesh, settings, surfaces[0].asset));
    std::vector<uint8_t> glb;
    ASSERT_TRUE(lt::writeSceneGlb(scene.document, scene.bin, surfaces, glb));
    lt::Asset asset;
    ASSERT_TRUE(lt::readAssetGlb(glb.data(), glb.size(), "duck.glb", asset));
    EXPECT_EQ(asset.faceUVs, scene.meshes[0].mesh.faceUVs);   // the cage's TEXCOORD_0 per corner
    ASSERT_FALSE(asset.faceUVs.empty());

    const OsdTexcoords osd(asset);
    for (float factor : {1.0f, 3.0f, 8.0f}) {
        SCOPED_TRACE(factor);
        lt::EvalSettings eval;
        eval.tessFactor = factor;
        lt::Tessellation soup;
        lt::evaluateCpu(asset, asset.positions.data(), eval, soup);
        ASSERT_EQ(soup.texcoords.size(), 2 * soup.vertexCount());
        double worst = 0;
        for (size_t i = 0; i < soup.vertexCount(); ++i) {
            double st[2];
            ASSERT_TRUE(osd.evaluate(int(soup.face[i]), soup.uv[2 * i], soup.uv[2 * i + 1], st));
            for (int k = 0; k < 2; ++k) worst = std::max(worst, std::fabs(st[k] - soup.texcoords[2 * i + size_t(k)]));
        }
        EXPECT_LT(worst, 1e-6) << "largest |texcoord - OpenSubdiv| at F = " << factor;
    }
}

// An asset without UVs has no texcoords.
TEST(Texcoords, NoneWithoutUVs) {
    lt::InputMesh tetra;
    tetra.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    tetra.faces = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    lt::Asset asset;
    ASSERT_TRUE(lt::bake(tetra, lt::BakeSettings{}, asset));
    lt::Tessellation soup;
    lt::evaluateCpu(asset, asset.positions.data(), lt::EvalSettings{}, soup);
    EXPECT_TRUE(soup.texcoords.empty());
    EXPECT_GT(soup.vertexCount(), 0u);
}

} // namespace
