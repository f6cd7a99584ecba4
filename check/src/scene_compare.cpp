// check/src/scene_compare.cpp -- lt::compareScene (looptess/tools/check.h): with a glTF --source,
// everything in the baked file but the surfaces is the source's.
//
// The source is read as loopbake reads it (parseGltfScene: buffers merged, images
// embedded, primitives the format cannot read given new accessors), so the two
// documents number their objects alike:
//   asset, scene(s), nodes, cameras, materials, textures, samplers, skins,
//   animations, top-level extensions and extras    equal JSON
//   images                                         same count, bytes and JSON
//   accessors and bufferViews of the source         equal JSON (bufferViews up to
//                                                   their place in the one buffer)
//                                                   and equal bytes
//   meshes                                          equal once the extension's
//                                                   objects are taken out
#include "looptess/tools/check.h"

#include "looptess/tools/file_io.h"
#include "looptess/glb.h"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace lt {
namespace {

// Unordered objects: JSON's member order means nothing, and tools that rewrite a
// glTF (ours among them) may reorder members, so equality ignores it.
using Json = nlohmann::json;

// A GLB's JSON document and BIN chunk.
Status splitGlb(const std::vector<uint8_t>& bytes, const std::string& name, Json& doc, std::vector<uint8_t>& bin) {
    GlbChunks chunks;
    if (Status st = readGlb(bytes.data(), bytes.size(), name, GlbLayout::Strict, chunks); !st) return st;
    doc = Json::parse(chunks.json.begin(), chunks.json.end(), nullptr, false);
    if (doc.is_discarded()) return Status::error(Status::BadInput, name + ": the JSON chunk is not JSON");
    bin.assign(chunks.bin, chunks.bin + chunks.binLength);
    return Status::ok();
}

// The bytes of bufferView `v` of a one-buffer document, or empty when out of range.
std::vector<uint8_t> viewBytes(const Json& doc, const std::vector<uint8_t>& bin, size_t v) {
    if (!doc.contains("bufferViews") || v >= doc["bufferViews"].size()) return {};
    const Json& view = doc["bufferViews"][v];
    const uint64_t at = view.value("byteOffset", uint64_t(0)), length = view.value("byteLength", uint64_t(0));
    if (at > bin.size() || length > bin.size() - at) return {};
    return std::vector<uint8_t>(bin.begin() + long(at), bin.begin() + long(at + length));
}

Json withoutSurface(Json mesh) {
    const char* ext = "EXT_mesh_loop_subdivision";
    auto strip = [&](Json& obj) {
        if (!obj.contains("extensions")) return;
        obj["extensions"].erase(ext);
        if (obj["extensions"].empty()) obj.erase("extensions");
    };
    strip(mesh);
    if (mesh.contains("primitives"))
        for (Json& p : mesh["primitives"]) strip(p);
    return mesh;
}

}  // namespace

Status compareScene(const std::string& assetPath, const std::string& sourcePath,
                    std::vector<std::string>& differences) {
    differences.clear();
    std::vector<uint8_t> assetBytes, sourceBytes;
    if (Status st = readFile(assetPath, assetBytes); !st) return st;
    if (Status st = readFile(sourcePath, sourceBytes); !st) return st;
    const std::string dir = std::filesystem::path(sourcePath).parent_path().string();
    GltfScene scene;
    if (Status st = parseGltfScene(sourceBytes.data(), sourceBytes.size(), sourcePath, dir.empty() ? "." : dir,
                                   Limits{}, scene);
        !st)
        return st;
    Json in = Json::parse(scene.document), out;
    std::vector<uint8_t> bin;
    if (Status st = splitGlb(assetBytes, assetPath, out, bin); !st) return st;
    auto differ = [&](const std::string& what) {
        if (differences.size() < 20) differences.push_back(what);
    };
    for (const char* key : {"scene", "scenes", "nodes", "cameras", "materials", "textures", "samplers", "skins",
                            "animations", "extensions", "extras"})
        if (in.value(key, Json()) != out.value(key, Json())) differ(std::string(key) + " differ");
    // asset: as it was, but the generator may name more tools after the source's.
    auto withoutGenerator = [](const Json& doc, std::string& generator) {
        Json asset = doc.value("asset", Json());
        const auto g = asset.is_object() ? asset.find("generator") : asset.end();
        generator = g != asset.end() && g->is_string() ? g->get<std::string>() : std::string();
        if (asset.is_object()) asset.erase("generator");
        return asset;
    };
    std::string inGenerator, outGenerator;
    if (withoutGenerator(in, inGenerator) != withoutGenerator(out, outGenerator) ||
        outGenerator.rfind(inGenerator, 0) != 0)
        differ("asset differs");
    auto count = [](const Json& doc, const char* key) { return doc.contains(key) ? doc[key].size() : size_t(0); };
    if (count(in, "images") != count(out, "images")) differ("the number of images differs");
    for (size_t i = 0; i < std::min(count(in, "images"), count(out, "images")); ++i) {
        const Json &a = in["images"][i], &b = out["images"][i];
        const bool sameBytes = viewBytes(in, scene.bin, a.value("bufferView", size_t(-1))) ==
                               viewBytes(out, bin, b.value("bufferView", size_t(-1)));
        if (!sameBytes || a.value("mimeType", "") != b.value("mimeType", "") ||
            a.value("name", "") != b.value("name", ""))
            differ("images[" + std::to_string(i) + "] differs");
    }
    for (size_t a = 0; a < count(in, "accessors"); ++a)
        if (a >= count(out, "accessors") || in["accessors"][a] != out["accessors"][a])
            differ("accessors[" + std::to_string(a) + "] differs");
    for (size_t v = 0; v < count(in, "bufferViews"); ++v) {
        Json a = in["bufferViews"][v], b = v < count(out, "bufferViews") ? out["bufferViews"][v] : Json();
        const bool sameBytes = viewBytes(in, scene.bin, v) == viewBytes(out, bin, v);
        for (Json* j : {&a, &b})
            if (j->is_object()) j->erase("byteOffset");
        if (!sameBytes || a != b) differ("bufferViews[" + std::to_string(v) + "] differs");
    }
    if (count(in, "meshes") != count(out, "meshes")) differ("the number of meshes differs");
    for (size_t m = 0; m < std::min(count(in, "meshes"), count(out, "meshes")); ++m)
        if (withoutSurface(out["meshes"][m]) != in["meshes"][m]) differ("meshes[" + std::to_string(m) + "] differs");
    return Status::ok();
}

}  // namespace lt
