// looprender: reading the scene around a GLB's surfaces (see scene.h).
//
// Every index and byte range from the file is checked before use; a problem throws
// Bad (inside this file only) and loadScene turns it into a BadInput Status that
// names the file and the glTF object ("Fox.glb: animations[0].samplers[2].input: ...").
#include "scene.h"

#include "looptess/glb.h"

#include <nlohmann/json.hpp>
#include <stb_image.h>

#include <cmath>
#include <cstring>
#include <limits>

namespace looprender {
namespace {

using Json = nlohmann::json;

constexpr uint64_t kMaxImagePixels = uint64_t(1) << 26;  // 64 M pixels, 256 MB decoded

struct Bad {
    std::string where, what;
};

// The JSON (parsed) and BIN chunks of a GLB.
struct Glb {
    Json json;
    const uint8_t* bin = nullptr;
    size_t binLength = 0;
};

Glb parseChunks(const lt::GlbChunks& chunks) {
    Glb g;
    g.json = Json::parse(chunks.json.begin(), chunks.json.end(), nullptr, false);
    g.bin = chunks.bin;
    g.binLength = chunks.binLength;
    if (!g.json.is_object()) throw Bad{"", "the JSON chunk is not a JSON object"};
    return g;
}

class Reader {
public:
    Reader(const Glb& glb, Scene& scene) : doc_(glb.json), glb_(glb), scene_(scene) {}

    void read() {
        nodes();
        roots();
        for (const Json& c : list("cameras")) {
            Scene::Camera cam;
            if (c.value("type", "") == "perspective" && c.contains("perspective")) {
                const Json& p = c["perspective"];
                cam.yfov = number(p, "yfov", 0.7f);
                cam.znear = number(p, "znear", 0.01f);
                cam.zfar = number(p, "zfar", 0.0f);
            }
            scene_.cameras.push_back(cam);
        }
        samplers();
        images();
        for (size_t t = 0; t < list("textures").size(); ++t) {
            const Json& tex = list("textures")[t];
            TextureRef r;
            r.image = optIndex(tex, "source", count("images"), "textures[" + std::to_string(t) + "]");
            r.sampler = optIndex(tex, "sampler", count("samplers"), "textures[" + std::to_string(t) + "]");
            scene_.textures.push_back(r);
        }
        materials();
        meshes();
        skins();
        animations();
    }

private:
    // --- JSON helpers ------------------------------------------------------------
    const Json& list(const char* key) const {
        static const Json empty = Json::array();
        auto it = doc_.find(key);
        return it != doc_.end() && it->is_array() ? *it : empty;
    }
    size_t count(const char* key) const { return list(key).size(); }
    static float number(const Json& o, const char* key, float fallback) {
        auto it = o.find(key);
        return it != o.end() && it->is_number() && std::isfinite(it->get<double>()) ? it->get<float>() : fallback;
    }
    static std::vector<float> numberList(const Json& o, const char* key) {
        std::vector<float> out;
        auto it = o.find(key);
        if (it != o.end() && it->is_array())
            for (const Json& v : *it) out.push_back(v.is_number() ? v.get<float>() : 0.0f);
        return out;
    }
    static void numbers(const Json& o, const char* key, float* out, size_t n) {
        auto it = o.find(key);
        if (it == o.end() || !it->is_array() || it->size() != n) return;
        for (size_t i = 0; i < n; ++i)
            if ((*it)[i].is_number()) out[i] = (*it)[i].get<float>();
    }
    // An index member that must be below `limit` when present; -1 when absent.
    static int optIndex(const Json& o, const char* key, size_t limit, const std::string& where) {
        auto it = o.find(key);
        if (it == o.end()) return -1;
        if (!it->is_number_unsigned() || it->get<uint64_t>() >= limit)
            throw Bad{where + "." + key, "not an index below " + std::to_string(limit)};
        return int(it->get<uint64_t>());
    }

    // --- accessors ---------------------------------------------------------------
    struct Span {
        const uint8_t* data = nullptr;
        size_t count = 0, comps = 0, stride = 0, size = 0;  // size: bytes of one component
        int type = 0;
        bool normalized = false;
    };
    Span accessor(uint64_t index, const std::string& where) const {
        const Json& accessors = list("accessors");
        if (index >= accessors.size()) throw Bad{where, "no accessor " + std::to_string(index)};
        const Json& a = accessors[index];
        const std::string at = "accessors[" + std::to_string(index) + "]";
        static const std::pair<const char*, size_t> kTypes[] = {
            {"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT4", 16}};
        Span s;
        for (auto& [name, n] : kTypes)
            if (a.value("type", "") == name) s.comps = n;
        s.type = a.value("componentType", 0);
        s.size = s.type == 5126 || s.type == 5125   ? 4
                 : s.type == 5123 || s.type == 5122 ? 2
                 : s.type == 5121 || s.type == 5120 ? 1
                                                    : 0;
        if (!s.comps || !s.size) throw Bad{at, "unknown type or componentType"};
        if (a.contains("sparse")) throw Bad{at, "sparse accessors are not supported here"};
        s.count = a.value("count", uint64_t(0));
        s.normalized = a.value("normalized", false);
        int view = optIndex(a, "bufferView", count("bufferViews"), at);
        if (view < 0) throw Bad{at, "no bufferView"};
        const Json& v = list("bufferViews")[size_t(view)];
        if (v.value("buffer", uint64_t(0)) != 0 || !glb_.bin) throw Bad{at, "data outside the GLB's BIN chunk"};
        uint64_t viewOffset = v.value("byteOffset", uint64_t(0)), viewLength = v.value("byteLength", uint64_t(0));
        uint64_t offset = a.value("byteOffset", uint64_t(0));
        s.stride = v.value("byteStride", uint64_t(0));
        if (s.stride == 0) s.stride = s.comps * s.size;
        if (s.count > viewLength || s.stride > 256) throw Bad{at, "count or byteStride out of range"};
        const uint64_t need = s.count == 0 ? 0 : offset + (s.count - 1) * s.stride + s.comps * s.size;
        if (viewOffset > glb_.binLength || viewLength > glb_.binLength - viewOffset || need > viewLength)
            throw Bad{at, "its bytes run past its bufferView or the BIN chunk"};
        s.data = glb_.bin + viewOffset + offset;
        return s;
    }
    static double component(const Span& s, size_t i, size_t c) {
        const uint8_t* p = s.data + i * s.stride + c * s.size;
        switch (s.type) {
        case 5126: {
            float f;
            std::memcpy(&f, p, 4);
            return f;
        }
        case 5125: {
            uint32_t u;
            std::memcpy(&u, p, 4);
            return u;
        }
        case 5123: {
            uint16_t u;
            std::memcpy(&u, p, 2);
            return s.normalized ? u / 65535.0 : u;
        }
        case 5122: {
            int16_t u;
            std::memcpy(&u, p, 2);
            return s.normalized ? std::max(u / 32767.0, -1.0) : u;
        }
        case 5121: return s.normalized ? p[0] / 255.0 : p[0];
        default: {
            int8_t u = int8_t(p[0]);
            return s.normalized ? std::max(u / 127.0, -1.0) : u;
        }
        }
    }
    std::vector<float> floats(uint64_t index, const std::string& where, size_t comps) const {
        Span s = accessor(index, where);
        if (s.comps != comps)
            throw Bad{where, "accessor " + std::to_string(index) + " has " + std::to_string(s.comps) + " components, " +
                                 std::to_string(comps) + " expected"};
        std::vector<float> out(s.count * comps);
        for (size_t i = 0; i < s.count; ++i)
            for (size_t c = 0; c < comps; ++c) {
                out[i * comps + c] = float(component(s, i, c));
                if (!std::isfinite(out[i * comps + c]))
                    throw Bad{where, "accessor " + std::to_string(index) + " has a non-finite value"};
            }
        return out;
    }

    // --- objects -------------------------------------------------------------------
    void nodes() {
        const Json& nodes = list("nodes");
        scene_.nodes.resize(nodes.size());
        for (size_t n = 0; n < nodes.size(); ++n) {
            const Json& j = nodes[n];
            const std::string at = "nodes[" + std::to_string(n) + "]";
            SceneNode& node = scene_.nodes[n];
            node.mesh = optIndex(j, "mesh", count("meshes"), at);
            node.skin = optIndex(j, "skin", count("skins"), at);
            node.camera = optIndex(j, "camera", count("cameras"), at);
            if (j.contains("matrix")) {
                node.hasMatrix = true;
                numbers(j, "matrix", node.matrix.data(), 16);
            }
            numbers(j, "translation", node.translation, 3);
            numbers(j, "rotation", node.rotation, 4);
            numbers(j, "scale", node.scale, 3);
            node.weights = numberList(j, "weights");
            if (j.contains("children") && j["children"].is_array())
                for (size_t c = 0; c < j["children"].size(); ++c) {
                    Json holder = {{"i", j["children"][c]}};
                    node.children.push_back(
                        uint32_t(optIndex(holder, "i", nodes.size(), at + ".children[" + std::to_string(c) + "]")));
                }
        }
        // A node hierarchy is a forest: no node is a child twice or its own ancestor.
        std::vector<int> parent(nodes.size(), -1);
        for (size_t n = 0; n < nodes.size(); ++n)
            for (uint32_t c : scene_.nodes[n].children) {
                if (parent[c] >= 0 || c == n)
                    throw Bad{"nodes[" + std::to_string(c) + "]", "has more than one parent or is its own child"};
                parent[c] = int(n);
            }
        for (size_t n = 0; n < nodes.size(); ++n) {  // cycles: walking up must end
            size_t steps = 0;
            for (int p = parent[n]; p >= 0; p = parent[size_t(p)])
                if (++steps > nodes.size())
                    throw Bad{"nodes[" + std::to_string(n) + "]", "is part of a cycle of children"};
        }
        parent_ = std::move(parent);
    }

    void roots() {
        const Json& scenes = list("scenes");
        int which = optIndex(doc_, "scene", scenes.size(), "glTF");
        if (which < 0 && !scenes.empty()) which = 0;
        if (which >= 0) {
            const Json& s = scenes[size_t(which)];
            if (s.contains("nodes") && s["nodes"].is_array())
                for (size_t i = 0; i < s["nodes"].size(); ++i) {
                    Json holder = {{"i", s["nodes"][i]}};
                    int n = optIndex(holder, "i", scene_.nodes.size(), "scenes[" + std::to_string(which) + "].nodes");
                    if (parent_[size_t(n)] >= 0)
                        throw Bad{"scenes[" + std::to_string(which) + "]", "names a node that is not a root"};
                    scene_.roots.push_back(uint32_t(n));
                }
        } else {
            for (size_t n = 0; n < scene_.nodes.size(); ++n)
                if (parent_[n] < 0) scene_.roots.push_back(uint32_t(n));
        }
    }

    void samplers() {
        for (const Json& s : list("samplers")) {
            SceneSampler out;
            out.magFilter = s.value("magFilter", out.magFilter);
            out.minFilter = s.value("minFilter", out.minFilter);
            out.wrapS = s.value("wrapS", out.wrapS);
            out.wrapT = s.value("wrapT", out.wrapT);
            scene_.samplers.push_back(out);
        }
    }

    void images() {
        const Json& images = list("images");
        for (size_t i = 0; i < images.size(); ++i) {
            const std::string at = "images[" + std::to_string(i) + "]";
            SceneImage image;
            int view = optIndex(images[i], "bufferView", count("bufferViews"), at);
            std::string mime = images[i].value("mimeType", "");
            if (view >= 0 && (mime == "image/png" || mime == "image/jpeg")) {
                const Json& v = list("bufferViews")[size_t(view)];
                uint64_t offset = v.value("byteOffset", uint64_t(0)), length = v.value("byteLength", uint64_t(0));
                if (!glb_.bin || offset > glb_.binLength || length > glb_.binLength - offset || length > INT32_MAX)
                    throw Bad{at, "its bufferView runs past the BIN chunk"};
                int w = 0, h = 0, comps = 0;
                if (!stbi_info_from_memory(glb_.bin + offset, int(length), &w, &h, &comps))
                    throw Bad{at, std::string("cannot decode its ") + mime + ": " + stbi_failure_reason()};
                if (uint64_t(w) * uint64_t(h) > kMaxImagePixels)
                    throw Bad{at, std::to_string(w) + " x " + std::to_string(h) + " pixels, more than " +
                                      std::to_string(kMaxImagePixels) + " (drawing it would take too much memory)"};
                stbi_uc* pixels = stbi_load_from_memory(glb_.bin + offset, int(length), &w, &h, &comps, 4);
                if (!pixels) throw Bad{at, std::string("cannot decode its ") + mime + ": " + stbi_failure_reason()};
                image.width = uint32_t(w);
                image.height = uint32_t(h);
                image.rgba.assign(pixels, pixels + size_t(w) * size_t(h) * 4);
                stbi_image_free(pixels);
            } else {
                scene_.warnings.push_back(at + ": " + (mime.empty() ? std::string("not in a bufferView") : mime) +
                                          " is not decoded here (PNG or JPEG in a bufferView); drawn white");
            }
            scene_.images.push_back(std::move(image));
        }
    }

    TextureRef texture(const Json& m, const char* key, const std::string& at) const {
        TextureRef r;
        auto it = m.find(key);
        if (it == m.end() || !it->is_object()) return r;
        int t = optIndex(*it, "index", scene_.textures.size(), at + "." + key);
        if (t < 0) return r;
        r = scene_.textures[size_t(t)];
        r.texCoord = it->value("texCoord", 0u);
        if (r.texCoord > 1) {
            scene_.warnings.push_back(at + "." + key + ": TEXCOORD_" + std::to_string(r.texCoord) +
                                      " is not drawn; TEXCOORD_0 used");
            r.texCoord = 0;
        }
        return r;
    }

    void materials() {
        const Json& materials = list("materials");
        for (size_t i = 0; i < materials.size(); ++i) {
            const Json& m = materials[i];
            const std::string at = "materials[" + std::to_string(i) + "]";
            SceneMaterial out;
            static const Json noPbr = Json::object();
            const Json& pbr = m.contains("pbrMetallicRoughness") ? m["pbrMetallicRoughness"] : noPbr;
            numbers(pbr, "baseColorFactor", out.baseColor, 4);
            out.metallic = number(pbr, "metallicFactor", 1);
            out.roughness = number(pbr, "roughnessFactor", 1);
            out.baseColorTexture = texture(pbr, "baseColorTexture", at + ".pbrMetallicRoughness");
            out.metallicRoughnessTexture = texture(pbr, "metallicRoughnessTexture", at + ".pbrMetallicRoughness");
            out.normalTexture = texture(m, "normalTexture", at);
            out.occlusionTexture = texture(m, "occlusionTexture", at);
            out.emissiveTexture = texture(m, "emissiveTexture", at);
            if (m.contains("normalTexture")) out.normalScale = number(m["normalTexture"], "scale", 1);
            if (m.contains("occlusionTexture")) out.occlusionStrength = number(m["occlusionTexture"], "strength", 1);
            numbers(m, "emissiveFactor", out.emissive, 3);
            out.mask = m.value("alphaMode", "OPAQUE") == "MASK";
            out.alphaCutoff = number(m, "alphaCutoff", 0.5f);
            out.doubleSided = m.value("doubleSided", false);
            if (m.value("alphaMode", "OPAQUE") == "BLEND")
                scene_.warnings.push_back(at + ": alphaMode BLEND is drawn opaque");
            scene_.materials.push_back(out);
        }
    }

    void meshes() {
        const Json& meshes = list("meshes");
        scene_.meshes.resize(meshes.size());
        for (size_t s = 0; s < scene_.surfaces.size(); ++s) {
            const lt::SceneSurface& surface = scene_.surfaces[s];
            SceneMesh& mesh = scene_.meshes[surface.mesh];
            mesh.surface = int(s);
            const Json& prims = meshes[surface.mesh]["primitives"];  // readSceneGlb checked the shape
            for (uint32_t k : surface.primitives) {
                const std::string at =
                    "meshes[" + std::to_string(surface.mesh) + "].primitives[" + std::to_string(k) + "]";
                mesh.materials.push_back(optIndex(prims[k], "material", scene_.materials.size(), at));
            }
            mesh.skin = skinWeights(surface, prims);
            morphTargets(surface, meshes[surface.mesh], mesh);
        }
    }

    // The cage primitives' POSITION morph targets per control vertex (the first
    // primitive vertex mapped to it gives them), and the mesh's default weights.
    void morphTargets(const lt::SceneSurface& surface, const Json& meshJson, SceneMesh& mesh) const {
        const Json& prims = meshJson["primitives"];
        const std::string at = "meshes[" + std::to_string(surface.mesh) + "]";
        const size_t vertices = surface.asset.controlVertexCount();
        size_t count = 0;
        for (size_t k = 0; k < surface.primitives.size(); ++k) {
            const Json& p = prims[surface.primitives[k]];
            const size_t n = p.contains("targets") && p["targets"].is_array() ? p["targets"].size() : 0;
            if (k == 0)
                count = n;
            else if (n != count)
                throw Bad{
                    at + ".primitives[" + std::to_string(surface.primitives[k]) + "]",
                    std::to_string(n) + " morph targets, the mesh's first cage primitive has " + std::to_string(count)};
        }
        if (count == 0) return;
        mesh.targets.assign(count, std::vector<float>(3 * vertices, 0.0f));
        std::vector<bool> done(vertices, false);
        for (size_t k = 0; k < surface.primitives.size(); ++k) {
            const Json& targets = prims[surface.primitives[k]]["targets"];
            const std::vector<uint32_t>& cv = surface.controlVertex[k];
            std::vector<std::vector<float>> d(count);
            for (size_t t = 0; t < count; ++t) {
                const std::string ta = at + ".primitives[" + std::to_string(surface.primitives[k]) + "].targets[" +
                                       std::to_string(t) + "].POSITION";
                if (!targets[t].is_object() || !targets[t].contains("POSITION")) continue;
                if (!targets[t]["POSITION"].is_number_unsigned()) throw Bad{ta, "not an accessor index"};
                d[t] = floats(targets[t]["POSITION"].get<uint64_t>(), ta, 3);
                if (d[t].size() != 3 * cv.size()) throw Bad{ta, "count differs from POSITION's"};
            }
            for (size_t v = 0; v < cv.size(); ++v) {
                if (done[cv[v]]) continue;
                done[cv[v]] = true;
                for (size_t t = 0; t < count; ++t)
                    if (!d[t].empty()) std::copy_n(&d[t][3 * v], 3, &mesh.targets[t][3 * size_t(cv[v])]);
            }
        }
        mesh.weights = numberList(meshJson, "weights");
        mesh.weights.resize(count, 0.0f);
    }

    // JOINTS_n / WEIGHTS_n (n = 0, 1) of the cage primitives per control vertex: the
    // first primitive vertex mapped to it gives them.
    SkinWeights skinWeights(const lt::SceneSurface& surface, const Json& prims) const {
        SkinWeights w;
        const size_t vertices = surface.asset.controlVertexCount();
        for (uint32_t set = 0; set < 2; ++set) {
            const std::string joints = "JOINTS_" + std::to_string(set), weights = "WEIGHTS_" + std::to_string(set);
            for (size_t k = 0; k < surface.primitives.size(); ++k) {
                const Json& attrs = prims[surface.primitives[k]]["attributes"];
                if (attrs.contains(joints) && attrs.contains(weights)) w.sets = set + 1;
            }
        }
        if (!w.sets) return w;
        w.joints.assign(vertices * 4 * w.sets, 0);
        w.weights.assign(vertices * 4 * w.sets, 0.0f);
        std::vector<bool> done(vertices, false);
        for (size_t k = 0; k < surface.primitives.size(); ++k) {
            const std::string at = "meshes[" + std::to_string(surface.mesh) + "].primitives[" +
                                   std::to_string(surface.primitives[k]) + "]";
            const Json& attrs = prims[surface.primitives[k]]["attributes"];
            const std::vector<uint32_t>& cv = surface.controlVertex[k];
            std::vector<std::vector<float>> j(w.sets), wt(w.sets);
            for (uint32_t set = 0; set < w.sets; ++set) {
                const std::string jn = "JOINTS_" + std::to_string(set), wn = "WEIGHTS_" + std::to_string(set);
                if (!attrs.contains(jn) || !attrs.contains(wn) || !attrs[jn].is_number_unsigned() ||
                    !attrs[wn].is_number_unsigned())
                    continue;
                j[set] = floats(attrs[jn].get<uint64_t>(), at + ".attributes." + jn, 4);
                wt[set] = floats(attrs[wn].get<uint64_t>(), at + ".attributes." + wn, 4);
                if (j[set].size() != cv.size() * 4 || wt[set].size() != cv.size() * 4)
                    throw Bad{at + ".attributes." + jn, "count differs from POSITION's"};
            }
            for (size_t v = 0; v < cv.size(); ++v) {
                if (done[cv[v]]) continue;
                done[cv[v]] = true;
                for (uint32_t set = 0; set < w.sets; ++set)
                    for (size_t c = 0; c < 4 && !j[set].empty(); ++c) {
                        const size_t o = (size_t(cv[v]) * w.sets + set) * 4 + c;
                        w.joints[o] = uint32_t(j[set][v * 4 + c]);
                        w.weights[o] = wt[set][v * 4 + c];
                    }
            }
        }
        return w;
    }

    void skins() {
        const Json& skins = list("skins");
        for (size_t s = 0; s < skins.size(); ++s) {
            const std::string at = "skins[" + std::to_string(s) + "]";
            SceneSkin skin;
            const Json& joints = skins[s].contains("joints") ? skins[s]["joints"] : Json::array();
            for (size_t i = 0; i < joints.size(); ++i) {
                Json holder = {{"i", joints[i]}};
                skin.joints.push_back(
                    uint32_t(optIndex(holder, "i", scene_.nodes.size(), at + ".joints[" + std::to_string(i) + "]")));
            }
            skin.inverseBind.assign(skin.joints.size(), Mat4{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
            if (skins[s].contains("inverseBindMatrices")) {
                std::vector<float> m =
                    floats(skins[s].value("inverseBindMatrices", uint64_t(0)), at + ".inverseBindMatrices", 16);
                if (m.size() != 16 * skin.joints.size())
                    throw Bad{at + ".inverseBindMatrices", "count differs from the joints'"};
                for (size_t i = 0; i < skin.joints.size(); ++i)
                    std::copy(m.begin() + 16 * i, m.begin() + 16 * (i + 1), skin.inverseBind[i].begin());
            }
            scene_.skins.push_back(std::move(skin));
        }
        // Every skinned mesh's joint indices must name a joint of the skins it is drawn with.
        for (size_t n = 0; n < scene_.nodes.size(); ++n) {
            const SceneNode& node = scene_.nodes[n];
            if (node.skin < 0 || node.mesh < 0) continue;
            const SkinWeights& w = scene_.meshes[size_t(node.mesh)].skin;
            const size_t joints = scene_.skins[size_t(node.skin)].joints.size();
            for (size_t i = 0; i < w.joints.size(); ++i)
                if (w.weights[i] != 0 && w.joints[i] >= joints)
                    throw Bad{"meshes[" + std::to_string(node.mesh) + "]",
                              "a vertex names joint " + std::to_string(w.joints[i]) + " but skins[" +
                                  std::to_string(node.skin) + "] has " + std::to_string(joints)};
        }
    }

    void animations() {
        const Json& animations = list("animations");
        for (size_t a = 0; a < animations.size(); ++a) {
            const Json& anim = animations[a];
            const std::string at = "animations[" + std::to_string(a) + "]";
            scene_.animations.push_back(anim.value("name", ""));
            if (!anim.contains("channels") || !anim.contains("samplers")) continue;
            const Json &channels = anim["channels"], &samplers = anim["samplers"];
            for (size_t c = 0; c < channels.size(); ++c) {
                const std::string ca = at + ".channels[" + std::to_string(c) + "]";
                const Json& target = channels[c].value("target", Json::object());
                const std::string path = target.value("path", "");
                int node = optIndex(target, "node", scene_.nodes.size(), ca + ".target");
                if (node < 0 || (path != "translation" && path != "rotation" && path != "scale" && path != "weights"))
                    continue;
                int s = optIndex(channels[c], "sampler", samplers.size(), ca);
                if (s < 0) throw Bad{ca, "no sampler"};
                const Json& sampler = samplers[size_t(s)];
                const std::string sa = at + ".samplers[" + std::to_string(s) + "]";
                AnimationChannel ch;
                ch.animation = uint32_t(a);
                ch.node = uint32_t(node);
                ch.path = path == "translation" ? AnimationChannel::Translation
                          : path == "rotation"  ? AnimationChannel::Rotation
                          : path == "scale"     ? AnimationChannel::Scale
                                                : AnimationChannel::Weights;
                const std::string interp = sampler.value("interpolation", "LINEAR");
                ch.interpolation = interp == "STEP"          ? AnimationChannel::Step
                                   : interp == "CUBICSPLINE" ? AnimationChannel::CubicSpline
                                                             : AnimationChannel::Linear;
                ch.times = floats(sampler.value("input", uint64_t(-1)), sa + ".input", 1);
                size_t comps = ch.path == AnimationChannel::Rotation ? 4 : 3;
                if (ch.path == AnimationChannel::Weights) {  // one per morph target of the node's mesh
                    const int mesh = scene_.nodes[size_t(node)].mesh;
                    comps = mesh < 0 ? 0 : scene_.meshes[size_t(mesh)].targets.size();
                    if (comps == 0) continue;  // weights of a mesh drawn without targets: nothing to move
                }
                ch.components = uint32_t(comps);
                ch.values = floats(sampler.value("output", uint64_t(-1)), sa + ".output",
                                   ch.path == AnimationChannel::Weights ? 1 : comps);
                const size_t perKey = comps * (ch.interpolation == AnimationChannel::CubicSpline ? 3 : 1);
                if (ch.times.empty() || ch.values.size() != ch.times.size() * perKey)
                    throw Bad{sa, "input and output counts do not match"};
                for (size_t k = 1; k < ch.times.size(); ++k)
                    if (!(ch.times[k] > ch.times[k - 1]))
                        throw Bad{sa + ".input", "key times are not strictly increasing"};
                scene_.channels.push_back(std::move(ch));
            }
        }
    }

    const Json& doc_;
    const Glb& glb_;
    Scene& scene_;
    std::vector<int> parent_;
};

}  // namespace

lt::Status loadScene(const uint8_t* data, size_t size, const std::string& name, Scene& out) {
    out = Scene{};
    lt::Status st = lt::readSceneGlb(data, size, name, out.surfaces);
    if (!st) return st;
    lt::GlbChunks chunks;
    if (st = lt::readGlb(data, size, name, lt::GlbLayout::Strict, chunks); !st) return st;
    try {
        Glb glb = parseChunks(chunks);
        Reader(glb, out).read();
    } catch (const Bad& bad) {
        return lt::Status::error(lt::Status::BadInput,
                                 name + ": " + (bad.where.empty() ? "" : bad.where + ": ") + bad.what);
    } catch (const nlohmann::json::exception& e) {
        return lt::Status::error(lt::Status::BadInput, name + ": unexpected JSON: " + e.what());
    } catch (const std::bad_alloc&) { return lt::Status::error(lt::Status::BadInput, name + ": too large to read"); }
    return lt::Status::ok();
}

}  // namespace looprender
