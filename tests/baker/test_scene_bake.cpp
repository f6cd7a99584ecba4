// tests/baker/test_scene_bake.cpp -- scene in, scene out: loopbake keeps every
// node, material, texture, image, sampler, skin, animation and camera of a glTF
// scene, every mesh becomes its own surface drawn in parts with its primitives'
// materials, and the Khronos glTF-Validator reports no error and no warning.
//
// The oracle is the input file itself: every object is compared with its input
// JSON, every input bufferView's bytes and every image's bytes with the output's.
#include "format_fixture.h"
#include "sanitizer.h"
#include "tool_run.h"

#include "looptess/asset.h"
#include "looptess/tools/check.h"
#include "looptess/glb.h"
#include "looptess/version.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

namespace fs = std::filesystem;

namespace {

using fmttest::Json;
using Bytes = std::vector<uint8_t>;

Bytes slurpBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return Bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

Bytes base64(const std::string& text, size_t start) {
    static const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    Bytes out;
    uint32_t acc = 0;
    int bits = 0;
    for (size_t i = start; i < text.size() && alphabet.find(text[i]) != std::string::npos; ++i) {
        acc = acc << 6 | uint32_t(alphabet.find(text[i]));
        if ((bits += 6) >= 8) out.push_back(uint8_t(acc >> (bits -= 8)));
    }
    return out;
}

// A glTF file's JSON and its buffers' bytes (GLB BIN, data URIs, sibling files).
struct Gltf {
    Json doc;
    std::vector<Bytes> buffers;

    explicit Gltf(const fs::path& file) {
        Bytes bytes = slurpBytes(file);
        Bytes bin;
        if (lt::isGlb(bytes.data(), bytes.size())) {  // read as loopbake reads its input
            lt::GlbChunks chunks;
            const lt::Status st =
                lt::readGlb(bytes.data(), bytes.size(), file.string(), lt::GlbLayout::Lenient, chunks);
            if (!st) throw std::runtime_error(st.message);
            doc = Json::parse(chunks.json.begin(), chunks.json.end());
            bin.assign(chunks.bin, chunks.bin + chunks.binLength);
        } else {
            doc = Json::parse(bytes);
        }
        for (const Json& b : doc.value("buffers", Json::array())) buffers.push_back(uri(b, file, bin));
    }

    static Bytes uri(const Json& obj, const fs::path& file, const Bytes& bin) {
        if (!obj.contains("uri")) return bin;
        const std::string u = obj["uri"];
        if (u.rfind("data:", 0) == 0) return base64(u, u.find(',') + 1);
        return slurpBytes(file.parent_path() / u);
    }

    Bytes view(size_t v) const {
        const Json& bv = doc["bufferViews"][v];
        const Bytes& b = buffers[bv.value("buffer", size_t(0))];
        const size_t at = bv.value("byteOffset", size_t(0));
        return Bytes(b.begin() + long(at), b.begin() + long(at + bv["byteLength"].get<size_t>()));
    }

    Bytes image(size_t i, const fs::path& file) const {
        const Json& im = doc["images"][i];
        return im.contains("bufferView") ? view(im["bufferView"]) : uri(im, file, {});
    }
};

fs::path workDir() {
    static const fs::path d = [] {
        fs::path p = fs::temp_directory_path() / ("looptess_scene_bake_" + std::to_string(getpid()));
        fs::create_directories(p);
        return p;
    }();
    return d;
}

// The Khronos glTF-Validator's report for a file (null when it did not run).
Json validatorReport(const fs::path& file) {
    const fs::path report = workDir() / (file.filename().string() + ".report.json");
    const std::string cmd =
        std::string("node '") + VALIDATOR_JS + "' '" + file.string() + "' > '" + report.string() + "' 2>&1";
    (void)std::system(cmd.c_str());  // exit 1 when the file has issues
    std::ifstream in(report);
    const Json r = Json::parse(in, nullptr, false);
    return r.is_discarded() || !r.contains("issues") ? Json() : r;
}

// The Khronos glTF-Validator's (errors, warnings) for a file.
std::pair<int, int> validatorIssues(const fs::path& file) {
    const Json r = validatorReport(file);
    if (r.is_null()) return {-1, -1};
    return {r["issues"]["numErrors"].get<int>(), r["issues"]["numWarnings"].get<int>()};
}

// Bakes `input` and checks the output against it (the header's oracle);
// `sameValidatorIssues`: the validator's counts must be the input's.
void expectSceneKept(const fs::path& input, bool sameValidatorIssues = true) {
    SCOPED_TRACE(input.string());
    const fs::path output = workDir() / (input.stem().string() + ".glb");
    const lt::test::RunResult bake =
        lt::test::runTool(LOOPBAKE_EXE, {input.string(), "-o", output.string()}, workDir());
    ASSERT_EQ(bake.exitCode, 0) << bake.err;
    const Gltf in(input), out(output);

    for (const char* key : {"scene", "scenes", "nodes", "cameras", "materials", "textures", "samplers", "skins",
                            "animations", "extensions", "extras", "extensionsRequired"})
        EXPECT_EQ(out.doc.value(key, Json()), in.doc.value(key, Json())) << key;
    // The asset object as it was, its generator chain ending with loopbake.
    Json asset = in.doc["asset"];
    const std::string ours = std::string("looptess loopbake ") + LOOPTESS_VERSION_STRING;
    asset["generator"] =
        asset.value("generator", "").empty() ? ours : asset["generator"].get<std::string>() + "; " + ours;
    EXPECT_EQ(out.doc["asset"], asset);
    // Accessors and bufferViews keep their indices and contents; the surfaces' tables
    // come after them.
    const size_t accessors = in.doc.value("accessors", Json::array()).size();
    for (size_t a = 0; a < accessors; ++a) EXPECT_EQ(out.doc["accessors"][a], in.doc["accessors"][a]) << a;
    const size_t views = in.doc.value("bufferViews", Json::array()).size();
    ASSERT_EQ(out.buffers.size(), 1u);
    for (size_t v = 0; v < views; ++v) {
        EXPECT_EQ(out.view(v), in.view(v)) << "bufferViews[" << v << "]";
        Json a = out.doc["bufferViews"][v], b = in.doc["bufferViews"][v];
        for (Json* j : {&a, &b}) j->erase("buffer"), j->erase("byteOffset");
        EXPECT_EQ(a, b) << "bufferViews[" << v << "]";
    }
    const size_t images = in.doc.value("images", Json::array()).size();
    ASSERT_EQ(out.doc.value("images", Json::array()).size(), images);
    for (size_t i = 0; i < images; ++i) {
        EXPECT_EQ(out.image(i, output), in.image(i, input)) << "images[" << i << "]";
        EXPECT_FALSE(out.doc["images"][i].contains("uri"));
        EXPECT_EQ(out.doc["images"][i].value("name", ""), in.doc["images"][i].value("name", ""));
    }
    // Meshes: as given but for the extension objects; every mesh of triangles a surface.
    std::vector<lt::SceneSurface> surfaces;
    const Bytes bytes = slurpBytes(output);
    const lt::Status st = lt::readSceneGlb(bytes.data(), bytes.size(), output.string(), surfaces);
    ASSERT_TRUE(st) << st.message;
    ASSERT_EQ(out.doc["meshes"].size(), in.doc["meshes"].size());
    size_t triangleMeshes = 0;
    for (size_t m = 0; m < in.doc["meshes"].size(); ++m) {
        Json mesh = out.doc["meshes"][m];
        const bool surface = mesh.contains("extensions") && mesh["extensions"].contains(fmttest::kExt);
        mesh["extensions"].erase(fmttest::kExt);
        if (mesh["extensions"].empty()) mesh.erase("extensions");
        for (Json& p : mesh["primitives"]) {
            if (!p.contains("extensions")) continue;
            p["extensions"].erase(fmttest::kExt);
            if (p["extensions"].empty()) p.erase("extensions");
        }
        EXPECT_EQ(mesh, in.doc["meshes"][m]) << "meshes[" << m << "]";
        triangleMeshes += surface;
    }
    EXPECT_EQ(surfaces.size(), triangleMeshes);
    // The validator finds nothing the input did not have (Duck, Fox, kenney: 0 and 0;
    // RobotExpressive ships with 752 errors about its skin weights).
    if (sameValidatorIssues) { EXPECT_EQ(validatorIssues(output), validatorIssues(input)); }
    // loopcheck --source's scene comparison (check.h compareScene) finds nothing.
    std::vector<std::string> differences;
    ASSERT_TRUE(lt::compareScene(output.string(), input.string(), differences));
    EXPECT_TRUE(differences.empty()) << differences.front();
}

const fs::path kData = LOOPTESS_TEST_DATA;

class SceneBake : public ::testing::Test {
protected:
    static void TearDownTestSuite() { fs::remove_all(workDir()); }
};

TEST_F(SceneBake, DuckKeepsItsTextureCameraAndNodes) {
    expectSceneKept(kData / "corpus" / "gltf" / "Duck.gltf");
    expectSceneKept(kData / "corpus" / "gltf" / "Duck.glb");
}

// A texture and a sampler from data URIs, embedded in the GLB.
TEST_F(SceneBake, BoxTexturedKeepsItsTexture) { expectSceneKept(kData / "scenes" / "BoxTextured.gltf"); }

// 13 meshes on 13 nodes, 7 materials: 13 surfaces, not one blob.
TEST_F(SceneBake, OrientationTestKeepsThirteenMeshes) { expectSceneKept(kData / "scenes" / "OrientationTest.gltf"); }

// Skinned and animated: skins, joints, animations, JOINTS_0/WEIGHTS_0 on the cage.
// KTX2 (KHR_texture_basisu) and WebP (EXT_texture_webp) images with their texture
// extensions pass through, embedded from data URIs with their MIME types. The
// validator (2.0.0-dev.3.10) supports EXT_texture_webp and decodes the WebP. It
// cannot validate KHR_texture_basisu: it does not recognise KTX2 data (a warning on
// the input too), and once the image sits in a bufferView, where glTF requires a
// mimeType, it does not know "image/ktx2" (VALUE_NOT_IN_LIST). Those two warnings on
// images[1] are the validator's limits; anything else fails.
TEST_F(SceneBake, Ktx2AndWebpImagesPassThroughWithTheirExtensions) {
    const fs::path input = kData / "scenes" / "texture_formats.gltf";
    expectSceneKept(input, false);
    EXPECT_EQ(validatorIssues(input), std::make_pair(0, 1));
    const Json report = validatorReport(workDir() / "texture_formats.glb");
    ASSERT_FALSE(report.is_null());
    EXPECT_EQ(report["issues"]["numErrors"], 0);
    std::vector<std::string> warnings;
    for (const Json& m : report["issues"]["messages"])
        if (m["severity"] == 1)
            warnings.push_back(m["code"].get<std::string>() + " " + m["pointer"].get<std::string>());
    std::sort(warnings.begin(), warnings.end());
    EXPECT_EQ(warnings, (std::vector<std::string>{"IMAGE_UNRECOGNIZED_FORMAT /images/1",
                                                  "VALUE_NOT_IN_LIST /images/1/mimeType"}));
    const Gltf out(workDir() / "texture_formats.glb");
    EXPECT_EQ(out.doc["images"][1].value("mimeType", ""), "image/ktx2");
    EXPECT_EQ(out.doc["images"][2].value("mimeType", ""), "image/webp");
    EXPECT_EQ(out.doc["textures"][0]["extensions"]["KHR_texture_basisu"]["source"], 1);
    EXPECT_EQ(out.doc["textures"][1]["extensions"]["EXT_texture_webp"]["source"], 2);
    const Json used = out.doc["extensionsUsed"];
    for (const char* ext : {"KHR_texture_basisu", "EXT_texture_webp", fmttest::kExt})
        EXPECT_NE(std::find(used.begin(), used.end(), ext), used.end()) << ext;
}

TEST_F(SceneBake, FoxKeepsItsSkinAndAnimations) { expectSceneKept(kData / "real" / "fox.glb"); }

// Welded copies of a vertex whose skin weights differ (the Fox with one copy's
// WEIGHTS_0 changed): skinned, they move apart and the surface follows one of them,
// so loopbake warns, naming the control vertex and both copies. The Fox as it is
// gets no such warning.
TEST_F(SceneBake, WeldedCopiesWithDifferentSkinWeightsWarn) {
    const fs::path fox = kData / "real" / "fox.glb", edited = workDir() / "fox_weights.glb";
    fmttest::Glb g(slurpBytes(fox));
    const Json& attributes = g.doc["meshes"][0]["primitives"][0]["attributes"];
    const int position = attributes["POSITION"], weights = attributes["WEIGHTS_0"];
    ASSERT_EQ(g.doc["accessors"][weights]["componentType"], 5126);
    const size_t count = g.doc["accessors"][position]["count"];
    auto weight = [&](size_t v, int k) {
        float x;
        std::memcpy(&x, g.element(weights, 4 * v + size_t(k)), 4);
        return x;
    };
    size_t copy = count;  // a vertex of two influences whose position an earlier vertex has too
    for (size_t v = 1; v < count && copy == count; ++v)
        for (size_t u = 0; u < v && copy == count && weight(v, 1) != 0; ++u)
            if (std::memcmp(g.element(position, 3 * u), g.element(position, 3 * v), 12) == 0) copy = v;
    ASSERT_LT(copy, count) << "the Fox has no welded copy with two influences";
    float w[4];
    std::memcpy(w, g.element(weights, 4 * copy), 16);
    const float changed[4] = {w[0] + w[1], 0.0f, w[2], w[3]};  // the second joint's weight moves to the first
    std::memcpy(g.element(weights, 4 * copy), changed, 16);
    const Bytes bytes = g.bytes();
    std::ofstream(edited, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), long(bytes.size()));

    const fs::path out = workDir() / "fox_weights_baked.glb";
    const lt::test::RunResult plain = lt::test::runTool(LOOPBAKE_EXE, {fox.string(), "-o", out.string()}, workDir());
    ASSERT_EQ(plain.exitCode, 0) << plain.err;
    EXPECT_EQ(plain.err.find("skin weights"), std::string::npos) << plain.err;
    const lt::test::RunResult r = lt::test::runTool(LOOPBAKE_EXE, {edited.string(), "-o", out.string()}, workDir());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("meshes[0]: control vertex "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("meshes[0].primitives[0] vertex " + std::to_string(copy) +
                         ", whose skin weights (JOINTS_n/WEIGHTS_n) differ"),
              std::string::npos)
        << r.err;
}

// EXT_mesh_manifold says which coincident vertices are one: two tetrahedra touching
// at a point (scripts/make_manifold_pinch.py) stay two closed surfaces (8 control
// vertices; by position their apexes would be one pinched vertex: 7), and the
// seam copy it merges joins. Without the extension, or with one the weld cannot
// use (a warning says why), the weld is by position.
TEST_F(SceneBake, ManifoldExtensionWeldsExactly) {
    const fs::path input = kData / "scenes" / "manifold_pinch.gltf";
    expectSceneKept(input);  // the extension passes through, still valid over the same accessors
    auto controlVertices = [&](const Json& doc, const std::string& stem, std::string* err = nullptr) {
        const fs::path in = workDir() / (stem + ".gltf"), out = workDir() / (stem + ".glb"),
                       json = workDir() / (stem + ".json");
        std::ofstream(in) << doc.dump();
        const lt::test::RunResult r =
            lt::test::runTool(LOOPBAKE_EXE, {in.string(), "-o", out.string(), "--json", json.string()}, workDir());
        EXPECT_EQ(r.exitCode, 0) << r.err;
        if (err) *err = r.err;
        std::ifstream report(json);
        return Json::parse(report)["meshes"][0]["vertices"].get<int>();
    };
    const Json doc = Gltf(input).doc;
    std::string err;
    EXPECT_EQ(controlVertices(doc, "manifold", &err), 8);
    EXPECT_EQ(err.find("EXT_mesh_manifold"), std::string::npos) << err;
    Json plain = doc;
    plain["meshes"][0].erase("extensions");
    plain.erase("extensionsUsed");
    EXPECT_EQ(controlVertices(plain, "by_position"), 7);
    Json broken = doc;  // primitive 1's indices in another bufferView than the manifold's
    broken["bufferViews"].push_back(broken["bufferViews"][1]);
    broken["accessors"][2]["bufferView"] = broken["bufferViews"].size() - 1;
    EXPECT_EQ(controlVertices(broken, "broken", &err), 7);
    EXPECT_NE(err.find("meshes[0].extensions.EXT_mesh_manifold: primitives[1].indices is not a range of the "
                       "manifoldPrimitive's indices"),
              std::string::npos)
        << err;
}

// A primitive whose indices get new accessors (a strip becomes a list) with an
// extension loopbake does not know, which may name the old ones: a warning names
// it; the extension passes through unchanged. A known one (KHR_materials_variants
// names no accessor) and primitives kept as they are get no warning.
TEST_F(SceneBake, ExtensionsOverRewrittenAccessorsWarn) {
    Json doc = Gltf(kData / "scenes" / "BoxTextured.gltf").doc;
    Json& prim = doc["meshes"][0]["primitives"][0];
    doc["accessors"][prim["indices"].get<int>()]["count"] = 3;  // one triangle,
    prim["mode"] = 5;                                           // as a TRIANGLE_STRIP: a new list
    prim["extensions"]["EXT_example_accessor_ref"] = {{"accessor", prim["indices"]}};
    doc["extensionsUsed"].push_back("EXT_example_accessor_ref");
    const fs::path in = workDir() / "strip_ext.gltf", out = workDir() / "strip_ext.glb";
    std::ofstream(in) << doc.dump();
    const lt::test::RunResult r = lt::test::runTool(LOOPBAKE_EXE, {in.string(), "-o", out.string()}, workDir());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("meshes[0].primitives[0]: indices got new accessors; EXT_example_accessor_ref may "
                         "still name the old ones"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(Gltf(out).doc["meshes"][0]["primitives"][0]["extensions"]["EXT_example_accessor_ref"],
              prim["extensions"]["EXT_example_accessor_ref"]);
    const lt::test::RunResult plain = lt::test::runTool(
        LOOPBAKE_EXE, {(kData / "scenes" / "BoxTextured.gltf").string(), "-o", out.string()}, workDir());
    EXPECT_EQ(plain.err.find("got new accessors"), std::string::npos) << plain.err;
}

// Skinned, with morph targets and triangles with a repeated index (no base faces).
TEST_F(SceneBake, RobotKeepsItsMorphTargets) { expectSceneKept(kData / "real" / "robotexpressive.glb"); }

// Several meshes and materials: each mesh its own surface, its parts their materials.
TEST_F(SceneBake, MultiMeshScenesKeepTheirPartsApart) {
    expectSceneKept(kData / "real" / "kenney_alien.glb");  // 6 meshes, 5 materials
    // 42 primitives; most of the test's 52 s under ASan, which the alien exercises too.
    if (!lt::test::kAsan) expectSceneKept(kData / "real" / "kenney_cake.glb");
}

// --mesh bakes only the meshes it names (by name or index); the others pass through
// as they were. The same input and settings give the same bytes.
TEST_F(SceneBake, MeshOptionBakesOnlyTheNamedMeshes) {
    const fs::path input = kData / "scenes" / "OrientationTest.gltf";
    const fs::path output = workDir() / "orientation_two.glb", again = workDir() / "orientation_again.glb";
    for (const fs::path& out : {output, again}) {
        const lt::test::RunResult r = lt::test::runTool(
            LOOPBAKE_EXE, {input.string(), "-o", out.string(), "--mesh", "BaseCubeMesh", "--mesh", "0"}, workDir());
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    EXPECT_EQ(slurpBytes(output), slurpBytes(again));
    const Gltf in(input), out(output);
    for (size_t m = 0; m < in.doc["meshes"].size(); ++m) {
        const bool baked = m == 0 || in.doc["meshes"][m]["name"] == "BaseCubeMesh";
        EXPECT_EQ(out.doc["meshes"][m].contains("extensions"), baked) << "meshes[" << m << "]";
        if (!baked) { EXPECT_EQ(out.doc["meshes"][m], in.doc["meshes"][m]) << "meshes[" << m << "]"; }
    }
    const lt::test::RunResult bad = lt::test::runTool(
        LOOPBAKE_EXE, {input.string(), "-o", (workDir() / "none.glb").string(), "--mesh", "NoSuchMesh"}, workDir());
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_NE(bad.err.find("--mesh NoSuchMesh: no mesh of triangles has that name or index"), std::string::npos)
        << bad.err;
    EXPECT_FALSE(fs::exists(workDir() / "none.glb"));
}

// A baked file baked again: a warning says so, and the new file reads back (its
// surface from the cage; the old tables, compressed or not, left unused).
TEST_F(SceneBake, ABakedFileBakedAgainWarns) {
    const fs::path input = kData / "scenes" / "BoxTextured.gltf";
    const fs::path once = workDir() / "box_once.glb", twice = workDir() / "box_twice.glb";
    ASSERT_EQ(lt::test::runTool(LOOPBAKE_EXE, {input.string(), "-o", once.string()}, workDir()).exitCode, 0);
    const lt::test::RunResult r = lt::test::runTool(LOOPBAKE_EXE, {once.string(), "-o", twice.string()}, workDir());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("meshes[0] was baked already"), std::string::npos) << r.err;
    const Bytes bytes = slurpBytes(twice);
    std::vector<lt::SceneSurface> surfaces;
    const lt::Status st = lt::readSceneGlb(bytes.data(), bytes.size(), twice.string(), surfaces);
    ASSERT_TRUE(st) << st.message;
    EXPECT_EQ(surfaces.size(), 1u);
}

// compareScene (loopcheck --source, M2) finds a changed material, node or image.
TEST_F(SceneBake, ACompareWithTheSourceFindsAChangedScene) {
    const fs::path input = kData / "scenes" / "BoxTextured.gltf", output = workDir() / "box.glb";
    ASSERT_EQ(lt::test::runTool(LOOPBAKE_EXE, {input.string(), "-o", output.string()}, workDir()).exitCode, 0);
    const Bytes baked = slurpBytes(output);
    const std::vector<std::pair<std::function<void(fmttest::Glb&)>, std::string>> edits = {
        {[](fmttest::Glb& g) { g.doc["materials"][0]["name"] = "changed"; }, "materials differ"},
        {[](fmttest::Glb& g) { g.doc["nodes"][0].erase("matrix"); }, "nodes differ"},
        {[](fmttest::Glb& g) {
             g.bin[g.doc["bufferViews"][g.doc["images"][0]["bufferView"].get<int>()].value("byteOffset", 0) + 100] ^= 1;
         },
         "images[0] differs"}};
    for (const auto& [edit, expected] : edits) {
        fmttest::Glb g(baked);
        edit(g);
        const fs::path changed = workDir() / "box_changed.glb";
        const Bytes bytes = g.bytes();
        std::ofstream(changed, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), long(bytes.size()));
        std::vector<std::string> differences;
        ASSERT_TRUE(lt::compareScene(changed.string(), input.string(), differences));
        ASSERT_FALSE(differences.empty()) << expected;
        EXPECT_EQ(differences.front(), expected);
    }
}

}  // namespace
