// tests/runtime/test_texcoords.cpp -- TEXCOORD_0, TEXCOORD_1 and COLOR_0 on the limit surface
// (CPU evaluation): every captured vertex's texcoord against OpenSubdiv's face-varying
// evaluation with FVAR_LINEAR_ALL at the same (face, u, v), through a Far::PatchTable
// with face-varying tables built here from the asset's control mesh and corner UVs.
// It pins the conventions too: which corner is (0,0), (1,0), (0,1) of a base face.
#include "looptess/asset.h"
#include "looptess/tools/baker.h"
#include "looptess/runtime.h"

#include <gtest/gtest.h>

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <algorithm>
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

// OpenSubdiv's face-varying values of `asset`'s base faces (`values`: `width` floats
// per face corner, as asset.faceUVs): a Loop refiner isolated to level 0 (one patch
// per base face) with one channel, one value per face corner, FVAR_LINEAR_ALL, and
// linear face-varying patches.
class OsdTexcoords {
public:
    OsdTexcoords(const lt::Asset& a, const std::vector<float>& values, int width) : values_(values), width_(width) {
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
        refiner_->RefineAdaptive(Far::TopologyRefiner::AdaptiveOptions(0));  // a patch per base face
        patches_.reset(Far::PatchTableFactory::Create(*refiner_, options));
        map_ = std::make_unique<Far::PatchMap>(*patches_);
    }

    bool evaluate(int face, double u, double v, double out[]) const {
        const Far::PatchTable::PatchHandle* h = map_->FindPatch(face, u, v);
        if (!h) return false;
        double w[20];
        patches_->EvaluateBasisFaceVarying<double>(*h, u, v, w);
        const auto cvs = patches_->GetPatchFVarValues(*h);
        std::fill(out, out + width_, 0.0);
        for (int i = 0; i < cvs.size(); ++i)
            for (int k = 0; k < width_; ++k) out[k] += w[i] * double(values_[size_t(width_ * cvs[i] + k)]);
        return true;
    }

    // The largest difference from `soup`'s values (`width` per vertex) at its vertices.
    double worst(const lt::Tessellation& soup, const std::vector<float>& emitted) const {
        double most = 0, exact[4];
        for (size_t i = 0; i < soup.vertexCount(); ++i) {
            if (!evaluate(int(soup.face[i]), soup.uv[2 * i], soup.uv[2 * i + 1], exact)) return INFINITY;
            for (int k = 0; k < width_; ++k)
                most = std::max(most, std::fabs(exact[k] - emitted[size_t(width_) * i + size_t(k)]));
        }
        return most;
    }

private:
    std::vector<float> values_;
    int width_;
    std::unique_ptr<Far::TopologyRefiner> refiner_;
    std::unique_ptr<Far::PatchTable> patches_;
    std::unique_ptr<Far::PatchMap> map_;
};

// The CPU evaluator's tessellation of `asset` at global factor `factor`.
lt::Tessellation soupAt(const lt::Asset& asset, float factor) {
    lt::EvalSettings eval;
    eval.tessFactor = factor;
    lt::Tessellation soup;
    lt::evaluateCpu(asset, asset.positions.data(), eval, soup);
    return soup;
}

// `file`'s first mesh baked to `maxDepth` in its scene, read back as the format gives it.
lt::Asset bakeScene(const std::string& file, int maxDepth, lt::InputMesh* mesh = nullptr) {
    const std::vector<uint8_t> bytes = slurp(file);
    lt::GltfScene scene;
    lt::Asset asset;
    EXPECT_TRUE(lt::parseGltfScene(bytes.data(), bytes.size(), file, "", lt::Limits{}, scene));
    if (scene.meshes.empty()) return asset;
    lt::BakeSettings settings;
    settings.maxDepth = maxDepth;
    std::vector<lt::SceneSurface> surfaces(1);
    surfaces[0].mesh = scene.meshes[0].index;
    surfaces[0].primitives = scene.meshes[0].primitives;
    surfaces[0].controlVertex = scene.meshes[0].controlVertex;
    EXPECT_TRUE(lt::bake(scene.meshes[0].mesh, settings, surfaces[0].asset));
    std::vector<uint8_t> glb;
    EXPECT_TRUE(lt::writeSceneGlb(scene.document, scene.bin, surfaces, glb));
    EXPECT_TRUE(lt::readAssetGlb(glb.data(), glb.size(), file, asset));
    if (mesh) *mesh = scene.meshes[0].mesh;
    return asset;
}

// The Duck's TEXCOORD_0 (4,212 faces, split at UV seams) baked from its glTF, read
// back as the format gives it, evaluated and compared.
TEST(Texcoords, EveryVertexMatchesOpenSubdivsLinearFaceVaryingValue) {
    lt::InputMesh mesh;
    const lt::Asset asset = bakeScene(std::string(LOOPTESS_CORPUS_DIR) + "/gltf/Duck.glb", 3, &mesh);
    EXPECT_EQ(asset.faceUVs, mesh.faceUVs);  // the cage's TEXCOORD_0 per corner
    ASSERT_FALSE(asset.faceUVs.empty());
    const OsdTexcoords osd(asset, asset.faceUVs, 2);
    for (float factor : {1.0f, 3.0f, 8.0f}) {
        const lt::Tessellation soup = soupAt(asset, factor);
        ASSERT_EQ(soup.texcoords.size(), 2 * soup.vertexCount());
        EXPECT_LT(osd.worst(soup, soup.texcoords), 1e-6) << "largest |texcoord - OpenSubdiv| at F = " << factor;
    }
}

// TEXCOORD_1 and COLOR_0 (tests/data/scenes/vertex_attributes.gltf): per corner from
// the cage primitives as glTF defines them -- unsigned bytes normalized (c / 255),
// RGB with alpha 1, (0, 0) and (1, 1, 1, 1) on a primitive without the attribute --
// and on the limit surface linear over each base face, as OpenSubdiv's
// FVAR_LINEAR_ALL.
TEST(Texcoords, SecondSetAndColoursFollowTheFaces) {
    const lt::Asset asset = bakeScene(std::string(LOOPTESS_TEST_DATA) + "/scenes/vertex_attributes.gltf", 4);
    ASSERT_EQ(asset.faceCount(), 8u);
    ASSERT_EQ(asset.faceUV1s.size(), 6u * 8);
    ASSERT_EQ(asset.faceColors.size(), 12u * 8);
    // Face 0 = primitive 0's (X, Y, Z): colours (127 + 120 x, 0, 127 + 120 z, 200) / 255.
    EXPECT_EQ(asset.faceColors[0], 247.0f / 255.0f);
    EXPECT_EQ(asset.faceColors[3], 200.0f / 255.0f);
    EXPECT_EQ(asset.faceUV1s[0], 0.25f);  // X: ((0 + 1) / 4, 0.75 - 1 / 4)
    EXPECT_EQ(asset.faceUV1s[1], 0.5f);
    for (size_t c = 12; c < 24; ++c) {  // faces 4..7: primitive 1, no TEXCOORD_1, RGB
        EXPECT_EQ(asset.faceUV1s[2 * c], 0.0f);
        EXPECT_EQ(asset.faceColors[4 * c + 3], 1.0f);
    }
    const OsdTexcoords second(asset, asset.faceUV1s, 2), colours(asset, asset.faceColors, 4);
    for (float factor : {1.0f, 5.0f, 16.0f}) {
        const lt::Tessellation soup = soupAt(asset, factor);
        ASSERT_EQ(soup.texcoords1.size(), 2 * soup.vertexCount());
        ASSERT_EQ(soup.colors.size(), 4 * soup.vertexCount());
        EXPECT_LT(second.worst(soup, soup.texcoords1), 1e-6) << "TEXCOORD_1 at F = " << factor;
        EXPECT_LT(colours.worst(soup, soup.colors), 1e-6) << "COLOR_0 at F = " << factor;
    }
}

// An asset without UVs has no texcoords.
TEST(Texcoords, NoneWithoutUVs) {
    lt::InputMesh tetra;
    tetra.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    tetra.faces = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    lt::Asset asset;
    ASSERT_TRUE(lt::bake(tetra, lt::BakeSettings{}, asset));
    const lt::Tessellation soup = soupAt(asset, 1.0f);
    EXPECT_TRUE(soup.texcoords.empty());
    EXPECT_TRUE(soup.texcoords1.empty());
    EXPECT_TRUE(soup.colors.empty());
    EXPECT_TRUE(soup.tangents.empty());
    EXPECT_GT(soup.vertexCount(), 0u);
}

}  // namespace
