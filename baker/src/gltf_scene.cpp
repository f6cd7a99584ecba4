// baker/src/gltf_scene.cpp -- lt::parseGltfScene: a glTF scene read for baking, kept
// whole (baker.h, GltfScene).
//
//   input:  buffers 0..k (GLB BIN, data URIs, files)   images (bufferViews, data URIs, files)
//   output: one buffer = | buffer 0 | buffer 1 | ... | image files and data URIs | rewritten accessors |
//           every bufferView rebased onto it; each image with a uri gets a bufferView
//           and its mimeType instead.
//
// Each mesh with primitives of triangles is one control mesh in its local space (no
// node transform: nodes instance the surface). Its cage primitives keep every
// attribute, material and extension; what the format cannot read as it is gets a new
// accessor (the old one stays, unused):
//   - POSITION that is not plain float (quantized, sparse, Draco), or with a copy of a
//     control vertex whose zero has the other sign than its first copy's;
//   - TEXCOORD_0 that is not plain float;
//   - indices of strips and fans (then mode 4), of Draco primitives, or sparse.
// A Draco primitive loses its extension; attributes only its payload held are
// dropped with a warning. POINTS and LINES primitives pass through untouched.
//
// Welding: every vertex of a mesh's cage primitives, by the bit pattern of its float
// xyz (-0 as +0), or exactly as the mesh's EXT_mesh_manifold says where it has one
// (gltf_manifold.h: coincident vertices that it keeps apart stay apart); control
// vertices numbered in order of first appearance (primitive order, vertex order),
// each at its first copy's position. A triangle with two
// corners at one control vertex is no base face (format rule "Scenes"), reported in
// one warning per mesh. The other triangles are cleaned (mesh_clean.h, on control
// vertices): one dropped leaves the cage as well, its primitive getting new indices
// without it, so that the cage's triangles stay the base faces. With
// InputOptions::hardEdges, the corners' NORMALs mark hard edges (hard_edges.h).
#include "looptess/tools/baker.h"
#include "looptess/version.h"

#include "gltf_manifold.h"
#include "gltf_primitive.h"
#include "gltf_source.h"
#include "hard_edges.h"
#include "mesh_clean.h"
#include "resource_limits.h"
#include "text.h"

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <functional>
#include <map>
#include <unordered_map>

namespace lt {
namespace {

using namespace gltf;
using Json = nlohmann::ordered_json;

std::string str(uint64_t v) { return std::to_string(v); }

class SceneReader {
public:
    SceneReader(const tinygltf::Model& model, const std::string& name, const InputOptions& options, GltfScene& out)
        : model_(model),
          name_(name),
          budget_(options.limits),
          cleaning_(options.cleaning),
          hardEdges_(options.hardEdges),
          out_(out) {
        for (const std::string& e : model.extensionsUsed) quantized_ = quantized_ || e == "KHR_mesh_quantization";
    }

    Status run(const std::string& text, const std::string& baseDir) {
        doc_ = Json::parse(text);
        Status st = references();
        if (st) st = mergeBuffers();
        if (st) st = embedImages(baseDir);
        for (size_t m = 0; st && m < model_.meshes.size(); ++m) st = readMesh(m);
        if (!st) return st;
        dropUnusedDraco();
        appendGenerator();
        if (!bin_.empty()) doc_["buffers"] = Json::array({Json{{"byteLength", bin_.size()}}});
        out_.document = doc_.dump();
        out_.bin = std::move(bin_);
        return Status::ok();
    }

private:
    const tinygltf::Model& model_;
    const std::string& name_;
    DecodeBudget budget_;
    InputCleaning cleaning_;
    bool hardEdges_;                              // InputOptions::hardEdges
    HardEdges hard_;                              // the mesh being read's corner normals, with hardEdges_
    std::vector<std::vector<uint32_t>> dropped_;  // per cage primitive of the mesh read: triangles cleaning dropped
    GltfScene& out_;
    bool quantized_ = false;
    Json doc_;
    std::vector<uint8_t> bin_;
    uint64_t inputBytes_ = 0;  // the buffers' bytes (for the images' share of the input limit)

    // Indices between objects that are kept as they are must name existing objects,
    // and the nodes form trees: the output would carry a broken reference or a cycle
    // on, unseen.
    Status references() const {
        const tinygltf::Model& m = model_;
        auto check = [&](int index, size_t count, const std::string& where, const char* what) {
            if (index < -1 || index >= int64_t(count))
                return badInput(name_ + ": " + where, std::string(what) + " " + str(uint64_t(int64_t(index))) +
                                                          " does not exist (" + str(count) + ")");
            return Status::ok();
        };
        Status st;
        for (size_t i = 0; st && i < m.nodes.size(); ++i) {
            const std::string at = "nodes[" + str(i) + "]";
            const tinygltf::Node& n = m.nodes[i];
            st = check(n.mesh, m.meshes.size(), at + ".mesh", "mesh");
            if (st) st = check(n.skin, m.skins.size(), at + ".skin", "skin");
            if (st) st = check(n.camera, m.cameras.size(), at + ".camera", "camera");
            for (size_t c = 0; st && c < n.children.size(); ++c)
                st = check(n.children[c], m.nodes.size(), at + ".children[" + str(c) + "]", "node");
        }
        std::vector<int> parent;
        if (st) st = nodeParents(m, name_, parent);
        if (st && !m.scenes.empty()) st = check(m.defaultScene, m.scenes.size(), "scene", "scene");
        for (size_t i = 0; st && i < m.scenes.size(); ++i)
            for (size_t j = 0; st && j < m.scenes[i].nodes.size(); ++j)
                st =
                    check(m.scenes[i].nodes[j], m.nodes.size(), "scenes[" + str(i) + "].nodes[" + str(j) + "]", "node");
        for (size_t i = 0; st && i < m.skins.size(); ++i) {
            const std::string at = "skins[" + str(i) + "]";
            const tinygltf::Skin& k = m.skins[i];
            st = check(k.skeleton, m.nodes.size(), at + ".skeleton", "node");
            if (st) st = check(k.inverseBindMatrices, m.accessors.size(), at + ".inverseBindMatrices", "accessor");
            for (size_t j = 0; st && j < k.joints.size(); ++j)
                st = check(k.joints[j], m.nodes.size(), at + ".joints[" + str(j) + "]", "node");
        }
        // loadModel keeps images from tinygltf: count them in the document.
        const size_t images = doc_.contains("images") ? doc_["images"].size() : 0;
        for (size_t i = 0; st && i < m.textures.size(); ++i) {
            st = check(m.textures[i].source, images, "textures[" + str(i) + "].source", "image");
            if (st) st = check(m.textures[i].sampler, m.samplers.size(), "textures[" + str(i) + "].sampler", "sampler");
        }
        for (size_t i = 0; st && i < m.animations.size(); ++i) {
            const tinygltf::Animation& a = m.animations[i];
            const std::string at = "animations[" + str(i) + "]";
            for (size_t c = 0; st && c < a.channels.size(); ++c) {
                st = check(a.channels[c].sampler, a.samplers.size(), at + ".channels[" + str(c) + "].sampler",
                           "sampler");
                if (st)
                    st = check(a.channels[c].target_node, m.nodes.size(), at + ".channels[" + str(c) + "].target.node",
                               "node");
            }
            for (size_t k = 0; st && k < a.samplers.size(); ++k) {
                st = check(a.samplers[k].input, m.accessors.size(), at + ".samplers[" + str(k) + "].input", "accessor");
                if (st)
                    st = check(a.samplers[k].output, m.accessors.size(), at + ".samplers[" + str(k) + "].output",
                               "accessor");
            }
        }
        return st;
    }

    // Every attribute of cage primitive `p` (morph targets included) has POSITION's count.
    Status attributeCounts(const tinygltf::Primitive& p, size_t vertices, const std::string& where) const {
        auto checkAll = [&](const std::map<std::string, int>& attributes, const std::string& at) {
            for (const auto& [semantic, index] : attributes) {
                if (index < 0 || size_t(index) >= model_.accessors.size())
                    return badInput(name_ + ": " + at + "." + excerpt(semantic),
                                    "accessor " + str(uint64_t(int64_t(index))) + " does not exist");
                if (model_.accessors[size_t(index)].count != vertices)
                    return badInput(name_ + ": " + at + "." + excerpt(semantic),
                                    "count " + str(model_.accessors[size_t(index)].count) +
                                        " differs from POSITION count " + str(vertices));
            }
            return Status::ok();
        };
        Status st = checkAll(p.attributes, where + ".attributes");
        for (size_t t = 0; st && t < p.targets.size(); ++t)
            st = checkAll(p.targets[t], where + ".targets[" + str(t) + "]");
        return st;
    }

    void align() {
        while (bin_.size() % 4 != 0) bin_.push_back(0);
    }

    // Every buffer into bin_, every bufferView rebased onto buffer 0.
    Status mergeBuffers() {
        std::vector<uint64_t> offset;
        for (size_t b = 0; b < model_.buffers.size(); ++b) {
            align();
            offset.push_back(bin_.size());
            const std::vector<unsigned char>& data = model_.buffers[b].data;
            bin_.insert(bin_.end(), data.begin(), data.end());
            inputBytes_ += data.size();
        }
        if (!doc_.contains("bufferViews")) return Status::ok();
        for (size_t i = 0; i < doc_["bufferViews"].size(); ++i) {
            Json& v = doc_["bufferViews"][i];
            const tinygltf::BufferView& view = model_.bufferViews[i];
            const size_t b = size_t(view.buffer);
            if (view.buffer < 0 || b >= offset.size() || view.byteOffset > model_.buffers[b].data.size() ||
                view.byteLength > model_.buffers[b].data.size() - view.byteOffset)
                return badInput(name_ + ": bufferViews[" + str(i) + "]", "lies outside its buffer");
            v["buffer"] = 0;
            v["byteOffset"] = offset[b] + view.byteOffset;
        }
        return Status::ok();
    }

    // A new bufferView over `bytes` (appended to bin_); its index.
    size_t addView(const uint8_t* bytes, size_t size, int target) {
        align();
        Json view = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", size}};
        if (target) view["target"] = target;
        bin_.insert(bin_.end(), bytes, bytes + size);
        doc_["bufferViews"].push_back(std::move(view));
        return doc_["bufferViews"].size() - 1;
    }

    Status embedImages(const std::string& baseDir) {
        if (!doc_.contains("images")) return Status::ok();
        uint64_t budget = budget_.limits().maxInputBytes - std::min(budget_.limits().maxInputBytes, inputBytes_);
        for (size_t i = 0; i < doc_["images"].size(); ++i) {
            Json& image = doc_["images"][i];
            if (!image.is_object() || !image.contains("uri")) continue;
            const std::string what = name_ + ": images[" + str(i) + "].uri";
            if (!image["uri"].is_string()) return badInput(what, "is not a string");
            std::vector<uint8_t> bytes;
            std::string mime, path;
            if (Status st = loadImageUri(image["uri"].get<std::string>(), what, baseDir, budget, bytes, mime, path);
                !st)
                return st;
            if (!path.empty()) out_.files.push_back(path);
            if (bytes.empty()) return badInput(what, "holds no bytes");
            image.erase("uri");
            image["bufferView"] = addView(bytes.data(), bytes.size(), 0);
            image["mimeType"] = mime;
        }
        return Status::ok();
    }

    // A new accessor of `values` (float, or u32 indices: componentType 5125).
    template <typename T>
    int addAccessor(const std::vector<T>& values, const char* type, int components, int target) {
        const size_t at = addView(reinterpret_cast<const uint8_t*>(values.data()), values.size() * 4, target);
        Json acc = {{"bufferView", at},
                    {"componentType", std::is_same_v<T, float> ? 5126 : 5125},
                    {"count", values.size() / size_t(components)},
                    {"type", type}};
        if (components == 3 && std::is_same_v<T, float>) {  // POSITION: bounds required
            Json lo = Json::array(), hi = Json::array();
            for (int k = 0; k < 3; ++k) {
                float a = values[size_t(k)], b = a;
                for (size_t i = size_t(k); i < values.size(); i += 3)
                    a = std::min(a, float(values[i])), b = std::max(b, float(values[i]));
                lo.push_back(double(a));
                hi.push_back(double(b));
            }
            acc["min"] = lo;
            acc["max"] = hi;
        }
        doc_["accessors"].push_back(std::move(acc));
        return int(doc_["accessors"].size() - 1);
    }

    // Whether accessor `index` is float data of `components` in a bufferView, not sparse.
    bool plainFloat(int index, int components) const {
        if (index < 0 || size_t(index) >= model_.accessors.size()) return false;
        const tinygltf::Accessor& a = model_.accessors[size_t(index)];
        return a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT && a.bufferView >= 0 && !a.sparse.isSparse &&
               tinygltf::GetNumComponentsInType(uint32_t(a.type)) == components;
    }

    Status readMesh(size_t m) {
        const tinygltf::Mesh& mesh = model_.meshes[m];
        GltfScene::Mesh sm;
        sm.index = uint32_t(m);
        sm.name = mesh.name;
        std::vector<Primitive> prims;
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            if (!isTriangles(mesh.primitives[p])) continue;
            Primitive prim;
            prim.where = "meshes[" + str(m) + "].primitives[" + str(p) + "]";
            Status st = readPrimitive(model_, mesh.primitives[p], quantized_, hardEdges_, name_ + ": " + prim.where,
                                      budget_, prim);
            const bool draco = mesh.primitives[p].extensions.count("KHR_draco_mesh_compression") != 0;
            if (st && !draco) st = attributeCounts(mesh.primitives[p], prim.vertexCount(), prim.where);
            if (!st) return st;
            sm.primitives.push_back(uint32_t(p));
            prims.push_back(std::move(prim));
        }
        if (prims.empty()) return Status::ok();
        if (mesh.extensions.count("EXT_mesh_loop_subdivision"))
            out_.warnings.push_back(name_ + ": meshes[" + str(m) +
                                    "] was baked already: baked again from its cage, its old tables stay in the "
                                    "file, unused (bake the source instead)");
        std::vector<uint32_t> merged;  // EXT_mesh_manifold's weld, if any
        std::string why;
        if (!manifoldMerges(model_, m, prims.front().positions, budget_, merged, why))
            out_.warnings.push_back(name_ + ": meshes[" + str(m) + "].extensions.EXT_mesh_manifold: " + why +
                                    "; welded by position instead");
        if (Status st = weld(prims, merged, sm); !st) return st;
        for (size_t k = 0; k < prims.size(); ++k) rewrite(prims[k], sm, k);
        out_.meshes.push_back(std::move(sm));
        return Status::ok();
    }

    // Control vertices, base faces and per-corner UVs of one mesh (header comment);
    // `merged` (EXT_mesh_manifold's representatives, or empty) replaces positions as
    // the weld key.
    Status weld(const std::vector<Primitive>& prims, const std::vector<uint32_t>& merged, GltfScene::Mesh& sm) {
        std::unordered_map<Key, uint32_t, KeyHash> ids;
        InputMesh& mesh = sm.mesh;
        const Limits& limits = budget_.limits();
        const std::string where = name_ + ": meshes[" + str(sm.index) + "]";
        bool anyUVs = false;
        std::vector<std::pair<uint32_t, uint32_t>> firstCopy;  // control vertex -> (primitive, vertex)
        size_t disagree = 0;
        std::string firstDisagreement;
        for (const Primitive& prim : prims) {
            anyUVs = anyUVs || !prim.uvs.empty();
            const uint32_t p = uint32_t(&prim - prims.data());
            std::vector<uint32_t>& cv = sm.controlVertex.emplace_back(prim.vertexCount());
            for (size_t v = 0; v < cv.size(); ++v) {
                float xyz[3];
                for (int k = 0; k < 3; ++k) xyz[k] = float(prim.positions[3 * v + size_t(k)]);
                const Key key = merged.empty() ? Key{weldBits(xyz[0]), weldBits(xyz[1]), weldBits(xyz[2])}
                                               : Key{merged[v], ~0u, ~0u};
                const auto [it, added] = ids.try_emplace(key, uint32_t(ids.size()));
                if (added && ids.size() > limits.maxVertices)
                    return badInput(where, "has " + limitMessage("at least " + str(ids.size()), "distinct vertices",
                                                                 limits.maxVertices, "--max-vertices"));
                if (added) mesh.positions.insert(mesh.positions.end(), xyz, xyz + 3);
                cv[v] = it->second;
                if (added) {
                    firstCopy.emplace_back(p, uint32_t(v));
                } else if (const auto [p0, v0] = firstCopy[it->second];
                           !sameInfluences(prims[p0], v0, prim, v) && disagree++ == 0) {
                    firstDisagreement = "control vertex " + str(it->second) + " joins " + prims[p0].where + " vertex " +
                                        str(v0) + " and " + prim.where + " vertex " + str(v);
                }
            }
        }
        if (disagree)
            out_.warnings.push_back(where + ": " + firstDisagreement +
                                    (disagree > 1 ? " (and " + str(disagree - 1) + " more copies)" : "") +
                                    ", whose skin weights (JOINTS_n/WEIGHTS_n) differ: skinned, the copies move "
                                    "apart and the surface follows one of them; give welded copies the same weights");
        size_t collapsed = 0;
        std::string first;
        FaceCleaner cleaner(mesh.positions, cleaning_);
        auto triangle = [&](uint64_t tag) {
            return prims[size_t(tag >> 32)].where + " triangle " + str(uint32_t(tag));
        };
        std::vector<uint32_t> kept;
        std::vector<FaceCleaner::Pending> zeroArea;
        dropped_.assign(prims.size(), {});
        hard_ = HardEdges{};
        for (size_t k = 0; k < prims.size(); ++k) {
            const Primitive& prim = prims[k];
            const std::vector<uint32_t>& cv = sm.controlVertex[k];
            for (size_t t = 0; t + 2 < prim.triangles.size(); t += 3) {
                const uint32_t* c = &prim.triangles[t];
                const uint32_t a = cv[c[0]], b = cv[c[1]], d = cv[c[2]];
                if (a == b || b == d || d == a) {
                    if (collapsed++ == 0) first = prim.where + " triangle " + str(t / 3);
                    continue;
                }
                const uint32_t abd[3] = {a, b, d};
                const uint64_t tag = uint64_t(k) << 32 | uint32_t(t / 3);
                const auto fate = cleaner.clean(abd, 3, tag, kept);
                if (fate == FaceCleaner::Fate::ZeroArea)
                    zeroArea.push_back({tag, uint32_t(mesh.faces.size() / 3), 1});
                else if (fate != FaceCleaner::Fate::Kept) {  // a duplicate
                    if (cleaning_ == InputCleaning::Refuse)
                        return badInput(name_ + ": " + triangle(tag), cleaner.defect(fate, triangle));
                    dropped_[k].push_back(uint32_t(t / 3));
                    continue;
                }
                if (mesh.faces.size() / 3 >= limits.maxFaces)
                    return badInput(where, "has " + limitMessage("more than " + str(limits.maxFaces), "triangles",
                                                                 limits.maxFaces, "--max-faces"));
                mesh.faces.insert(mesh.faces.end(), {a, b, d});
                if (hardEdges_) {
                    auto normal = [&](int j) {
                        return prim.normals.empty() ? nullptr : &prim.normals[3 * size_t(c[j])];
                    };
                    hard_.addFace(normal(0), normal(1), normal(2));
                }
                for (int j = 0; anyUVs && j < 3; ++j)
                    for (int q = 0; q < 2; ++q)
                        mesh.faceUVs.push_back(prim.uvs.empty() ? 0.0f : float(prim.uvs[2 * size_t(c[j]) + size_t(q)]));
            }
        }
        if (collapsed)
            out_.warnings.push_back(name_ + ": " + first +
                                    (collapsed > 1 ? " and " + str(collapsed - 1) + " more" : "") +
                                    ": two corners at one position (a line or a point, drawn as nothing); "
                                    "not a base face");
        if (Status st = settleZeroArea(cleaner, zeroArea, triangle, mesh); !st) return st;
        if (hardEdges_) hard_.addCreases(mesh);
        cleaner.warn(name_, "triangle", triangle, out_.warnings);
        mesh.cleaning = cleaner.report();
        mesh.cleaning.collapsed = uint32_t(collapsed);
        if (mesh.faces.empty())
            return badInput(where, mesh.cleaning.renumbered()
                                       ? "has no triangle left once input cleaning dropped its faces"
                                       : "has no triangle with three distinct corners");
        return Status::ok();
    }

    // The zero-area triangles cleaning drops (mesh_clean.h) leave the mesh and the cage.
    Status settleZeroArea(FaceCleaner& cleaner, const std::vector<FaceCleaner::Pending>& zeroArea,
                          const std::function<std::string(uint64_t)>& triangle, InputMesh& mesh) {
        const std::vector<size_t> gone = cleaner.settleZeroArea(mesh, zeroArea);
        if (gone.empty()) return Status::ok();
        if (cleaning_ == InputCleaning::Refuse)
            return badInput(name_ + ": " + triangle(zeroArea[gone[0]].tag),
                            cleaner.defect(FaceCleaner::Fate::ZeroArea, triangle));
        std::vector<uint8_t> drop(mesh.faceCount(), 0);
        for (size_t i : gone) {
            drop[zeroArea[i].first] = 1;
            dropped_[size_t(zeroArea[i].tag >> 32)].push_back(uint32_t(zeroArea[i].tag));
        }
        for (std::vector<uint32_t>& d : dropped_) std::sort(d.begin(), d.end());
        eraseTriangles(mesh, drop);
        if (hardEdges_) hard_.erase(drop);
        return Status::ok();
    }

    // New accessors where cage primitive k's cannot be read as the format reads them.
    void rewrite(const Primitive& prim, const GltfScene::Mesh& sm, size_t k) {
        const tinygltf::Primitive& p = model_.meshes[sm.index].primitives[sm.primitives[k]];
        Json& out = doc_["meshes"][sm.index]["primitives"][sm.primitives[k]];
        const bool draco = p.extensions.count("KHR_draco_mesh_compression") != 0;
        const std::vector<uint32_t>& cv = sm.controlVertex[k];
        std::vector<std::string> changed;  // what got new accessors
        auto pos = p.attributes.find("POSITION");
        bool exact = !draco && plainFloat(pos->second, 3);
        for (size_t i = 0; exact && i < 3 * cv.size(); ++i) {  // bitwise: -0 is not +0 here
            const float original = float(prim.positions[i]);
            exact = std::memcmp(&original, &sm.mesh.positions[3 * size_t(cv[i / 3]) + i % 3], 4) == 0;
        }
        if (!exact) {
            std::vector<float> xyz(3 * cv.size());
            for (size_t v = 0; v < cv.size(); ++v) std::memcpy(&xyz[3 * v], &sm.mesh.positions[3 * size_t(cv[v])], 12);
            out["attributes"]["POSITION"] = addAccessor(xyz, "VEC3", 3, 34962);
            changed.push_back("POSITION");
        }
        auto uv = p.attributes.find("TEXCOORD_0");
        if (uv != p.attributes.end() && (draco || !plainFloat(uv->second, 2))) {
            std::vector<float> st(prim.uvs.begin(), prim.uvs.end());
            out["attributes"]["TEXCOORD_0"] = addAccessor(st, "VEC2", 2, 34962);
            changed.push_back("TEXCOORD_0");
        }
        const bool listed = p.mode == -1 || p.mode == TINYGLTF_MODE_TRIANGLES;
        const bool sparseIndices = p.indices >= 0 && model_.accessors[size_t(p.indices)].sparse.isSparse;
        const std::vector<uint32_t>& dropped = dropped_[k];  // ascending
        if (draco || !listed || sparseIndices || !dropped.empty()) {
            std::vector<uint32_t> triangles;
            triangles.reserve(prim.triangles.size() - 3 * dropped.size());
            for (size_t t = 0, d = 0; t < prim.triangles.size() / 3; ++t) {
                if (d < dropped.size() && dropped[d] == t)
                    ++d;
                else
                    triangles.insert(triangles.end(), &prim.triangles[3 * t], &prim.triangles[3 * t + 3]);
            }
            out["indices"] = addAccessor(triangles, "SCALAR", 1, 34963);
            if (!listed) out["mode"] = 4;
            changed.push_back("indices");
        }
        warnExtensions(sm, k, changed);
        if (!draco) return;
        out["extensions"].erase("KHR_draco_mesh_compression");
        if (out["extensions"].empty()) out.erase("extensions");
        for (const auto& [semantic, index] : p.attributes) {
            if (semantic == "POSITION" || semantic == "TEXCOORD_0" || model_.accessors[size_t(index)].bufferView >= 0)
                continue;
            out["attributes"].erase(semantic);
            out_.warnings.push_back(name_ + ": meshes[" + str(sm.index) + "].primitives[" + str(sm.primitives[k]) +
                                    "]: attribute " + excerpt(semantic) +
                                    " was only in the Draco payload; dropped (the surface has its own normals)");
        }
    }

    // Extensions on a primitive that got new accessors, or on its mesh, may name the
    // old ones (EXT_mesh_manifold does: its manifoldPrimitive shares the primitives'
    // POSITION and indices): a warning names each that loopbake cannot vouch for.
    void warnExtensions(const GltfScene::Mesh& sm, size_t k, const std::vector<std::string>& changed) {
        if (changed.empty()) return;
        const size_t m = sm.index, p = sm.primitives[k];
        std::string names;
        auto collect = [&](const tinygltf::ExtensionMap& extensions, const std::string& where) {
            for (const auto& e : extensions) {
                const std::string& n = e.first;
                if (n == "KHR_draco_mesh_compression" || n == "KHR_materials_variants" ||
                    n == "EXT_mesh_loop_subdivision")
                    continue;  // handled here, or names no accessor
                names += (names.empty() ? "" : ", ") + where + excerpt(n);
            }
        };
        collect(model_.meshes[m].primitives[p].extensions, "");
        collect(model_.meshes[m].extensions, "the mesh's ");
        if (names.empty()) return;
        std::string what;
        for (const std::string& c : changed) what += (what.empty() ? "" : ", ") + c;
        out_.warnings.push_back(name_ + ": meshes[" + str(m) + "].primitives[" + str(p) + "]: " + what +
                                " got new accessors; " + names +
                                " may still name the old ones: loopbake passes it through unchanged, check it");
    }

    // asset.generator names every tool that wrote the file, the first first:
    // "Khronos Blender glTF 2.0 exporter; looptess loopbake 0.1.0".
    void appendGenerator() {
        Json& asset = doc_["asset"];
        const std::string ours = std::string("looptess loopbake ") + LOOPTESS_VERSION_STRING;
        const auto before = asset.find("generator");
        const bool chain =
            before != asset.end() && before->is_string() && !before->get_ref<const std::string&>().empty();
        asset["generator"] = chain ? before->get<std::string>() + "; " + ours : ours;
    }

    // KHR_draco_mesh_compression leaves extensionsUsed/Required once no primitive has it.
    void dropUnusedDraco() {
        if (doc_.contains("meshes"))
            for (const Json& mesh : doc_["meshes"])
                for (const Json& p : mesh.value("primitives", Json::array()))
                    if (p.contains("extensions") && p["extensions"].contains("KHR_draco_mesh_compression")) return;
        for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
            if (!doc_.contains(list)) continue;
            Json& l = doc_[list];
            l.erase(std::remove(l.begin(), l.end(), "KHR_draco_mesh_compression"), l.end());
            if (l.empty()) doc_.erase(list);
        }
    }
};

}  // namespace

Status parseGltfScene(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir,
                      const Limits& limits, GltfScene& scene) {
    InputOptions options;
    options.limits = limits;
    return parseGltfScene(data, size, name, baseDir, options, scene);
}

Status parseGltfScene(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir,
                      const InputOptions& options, GltfScene& scene) {
    const Limits& limits = options.limits;
    GltfScene result;
    Status st;
    try {
        tinygltf::Model model;
        std::string text;
        st = loadModel(data, size, name, baseDir, limits, model, result.warnings, &text, &result.files);
        if (st) st = SceneReader(model, name, options, result).run(text, baseDir);
        for (GltfScene::Mesh& m : result.meshes)
            if (options.boundary) m.mesh.boundary = *options.boundary;
    } catch (const std::bad_alloc&) {
        st = Status::error(Status::Internal, name + ": out of memory");
    } catch (const std::exception& e) { st = Status::error(Status::BadInput, name + ": " + shortenQuotes(e.what())); }
    if (st && result.meshes.empty()) st = badInput(name, "no mesh has a primitive of triangles");
    if (st) {
        scene = std::move(result);
    } else {
        scene = GltfScene{};
        scene.warnings = std::move(result.warnings);
    }
    return st;
}

}  // namespace lt
