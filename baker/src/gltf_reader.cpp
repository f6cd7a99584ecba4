// baker/src/gltf_reader.cpp -- lt::parseGltf: scene traversal, node transforms,
// TRIANGLES primitives (plain and KHR_draco_mesh_compression), welding by position.
//
// Loading and checking the file is gltf_source.cpp, accessors gltf_accessor.cpp,
// Draco gltf_draco.cpp. Here:
//   - the scene is the default scene, else scene 0, else every node without a parent;
//     nodes must form trees (one parent each, scene roots parentless, no repeats);
//   - each node's world matrix (matrix, or T * R * S, times its parent's) is kept in
//     double; a position is transformed in double and rounded to float once;
//   - a mesh's primitives are read once, however many nodes instance it;
//   - corners are welded by the bit pattern of their transformed float xyz (-0 taken
//     as +0), control vertices numbered in order of first use (node order, primitive
//     order, face order, corner order): deterministic, and unused vertices drop out;
//   - a triangle with two corners at one position (a repeated index, or corners the
//     weld joins) is a line or a point: glTF viewers draw nothing for it, so it is
//     dropped, with one warning naming the count and the first (node, mesh,
//     primitive, triangle). OBJ faces are kept and refused instead: tags address
//     them by index;
//   - the other triangles are cleaned on their welded vertices (mesh_clean.h); the
//     vertices of a zero-area one dropped stay, unused, where no other triangle has
//     them;
//   - a negative-determinant world matrix swaps corners 1 and 2 of its triangles so
//     faces stay counter-clockwise seen from outside;
//   - TEXCOORD_0 is kept per corner, as stored in glTF (v down, origin top-left);
//   - with InputOptions::hardEdges, NORMAL is read per corner (transformed by the
//     world matrix's cofactor matrix) and split normals become creases (hard_edges.h).
#include "looptess/tools/baker.h"

#include "gltf_accessor.h"
#include "gltf_primitive.h"
#include "gltf_source.h"
#include "hard_edges.h"
#include "mesh_clean.h"
#include "resource_limits.h"
#include "text.h"

#include <algorithm>
#include <tiny_gltf.h>

#include <array>
#include <cmath>
#include <cstring>
#include <new>
#include <unordered_map>

namespace lt {
namespace {

using namespace gltf;

template <class T>
std::string str(T v) {
    return std::to_string(v);
}

using Matrix = std::array<double, 16>;  // column-major, as glTF: m[col * 4 + row]

Matrix identity() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }

Matrix multiply(const Matrix& a, const Matrix& b) {
    Matrix c{};
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += a[k * 4 + row] * b[col * 4 + k];
            c[col * 4 + row] = s;
        }
    return c;
}

double determinant3(const Matrix& m) {
    return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
           m[8] * (m[1] * m[6] - m[5] * m[2]);
}

// How `m` maps normals: its 3x3 part's cofactor matrix (det * inverse transpose),
// negated where det < 0 so normals keep their side; column-major 3x3.
std::array<double, 9> normalMatrix(const Matrix& m) {
    auto at = [&](int row, int col) { return m[col * 4 + row]; };
    std::array<double, 9> c{};
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) {
            const int r0 = (row + 1) % 3, r1 = (row + 2) % 3, c0 = (col + 1) % 3, c1 = (col + 2) % 3;
            c[col * 3 + row] = at(r0, c0) * at(r1, c1) - at(r0, c1) * at(r1, c0);
        }
    if (determinant3(m) < 0)
        for (double& x : c) x = -x;
    return c;
}

bool finiteOfSize(const std::vector<double>& v, size_t n) {
    if (v.size() != n) return false;
    for (double x : v)
        if (!std::isfinite(x)) return false;
    return true;
}

// A node's local transform: its matrix (affine), or translation * rotation * scale
// with the rotation quaternion normalized.
Status localTransform(const tinygltf::Node& n, const std::string& where, Matrix& m) {
    if (!n.matrix.empty()) {
        if (!finiteOfSize(n.matrix, 16)) return badInput(where, "matrix is not 16 finite numbers");
        if (n.matrix[3] != 0 || n.matrix[7] != 0 || n.matrix[11] != 0 || n.matrix[15] != 1)
            return badInput(where, "matrix is not affine (last row must be 0 0 0 1)");
        std::copy(n.matrix.begin(), n.matrix.end(), m.begin());
        return Status::ok();
    }
    const auto& t = n.translation;
    const auto& r = n.rotation;
    const auto& s = n.scale;
    if ((!t.empty() && !finiteOfSize(t, 3)) || (!r.empty() && !finiteOfSize(r, 4)) ||
        (!s.empty() && !finiteOfSize(s, 3)))
        return badInput(where, "translation, rotation or scale has the wrong size or is not finite");
    double x = 0, y = 0, z = 0, w = 1;
    if (!r.empty()) {
        const double len = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3]);
        if (!(len > 0) || !std::isfinite(len)) return badInput(where, "rotation is not a quaternion");
        x = r[0] / len, y = r[1] / len, z = r[2] / len, w = r[3] / len;
    }
    const double rot[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                              {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                              {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    m = identity();
    for (int col = 0; col < 3; ++col) {
        const double sc = s.empty() ? 1.0 : s[col];
        for (int row = 0; row < 3; ++row) m[col * 4 + row] = rot[row][col] * sc;
        if (!t.empty()) m[12 + col] = t[col];
    }
    return Status::ok();
}

// Bit pattern of a welded position.
class Reader {
public:
    Reader(const tinygltf::Model& model, const std::string& name, const InputOptions& options, InputMesh& mesh)
        : model_(model),
          name_(name),
          mesh_(mesh),
          meshes_(model.meshes.size()),
          loaded_(model.meshes.size(), 0),
          budget_(options.limits),
          cleaning_(options.cleaning),
          cleaner_(mesh.positions, options.cleaning),
          hardEdges_(options.hardEdges) {
        for (const std::string& e : model.extensionsUsed) quantized_ = quantized_ || e == "KHR_mesh_quantization";
    }

    Status run() {
        std::vector<int> roots;
        Status st = sceneRoots(roots);
        std::vector<char> visited(model_.nodes.size(), 0);
        std::vector<std::pair<int, Matrix>> stack;  // node, parent's world matrix
        for (size_t i = roots.size(); st && i-- > 0;) stack.push_back({roots[i], identity()});
        while (st && !stack.empty()) {
            const auto [index, parent] = stack.back();
            stack.pop_back();
            const std::string where = name_ + ": nodes[" + str(index) + "]";
            if (visited[size_t(index)]++) return badInput(where, "is listed twice in the scene");
            const tinygltf::Node& node = model_.nodes[size_t(index)];
            Matrix local;
            if (!(st = localTransform(node, where, local))) break;
            const Matrix world = multiply(parent, local);
            if (node.mesh >= 0 || node.mesh < -1) st = instance(node.mesh, world, where);
            for (size_t c = node.children.size(); st && c-- > 0;) stack.push_back({node.children[c], world});
        }
        if (!st) return st;
        if (mesh_.faces.empty())
            return badInput(name_, "no TRIANGLES primitive in the scene (" + str(roots.size()) + " root nodes)");
        if (collapsed_ != 0)
            mesh_.warnings.push_back(firstCollapsed_ + (collapsed_ > 1 ? " and " + str(collapsed_ - 1) + " more" : "") +
                                     ": two corners at one position (a line or a point, drawn as nothing); "
                                     "dropped");
        if (!uvsComplete_ && anyUVs_) {
            mesh_.faceUVs.clear();
            mesh_.warnings.push_back(name_ + ": some primitives have no TEXCOORD_0; UVs dropped");
        }
        if (!(st = settleZeroArea())) return st;
        if (hardEdges_) hard_.addCreases(mesh_);
        cleaner_.warn(
            name_, "triangle", [&](uint64_t tag) { return triangle(tag); }, mesh_.warnings);
        mesh_.cleaning = cleaner_.report();
        mesh_.cleaning.collapsed = uint32_t(collapsed_);
        if (mesh_.faces.empty()) return badInput(name_, "no triangle is left once input cleaning dropped its faces");
        mesh_.faceUVs.shrink_to_fit();
        return Status::ok();
    }

private:
    const tinygltf::Model& model_;
    const std::string& name_;
    InputMesh& mesh_;
    bool quantized_ = false;
    std::vector<std::vector<Primitive>> meshes_;  // TRIANGLES primitives, per mesh
    std::vector<char> loaded_;                    // meshes_[i] is filled
    DecodeBudget budget_;
    std::unordered_map<Key, uint32_t, KeyHash> weld_;
    bool uvsComplete_ = true, anyUVs_ = false;  // every / some appended primitive has UVs
    size_t collapsed_ = 0;                      // triangles dropped: two corners at one position
    std::string firstCollapsed_;
    InputCleaning cleaning_;
    FaceCleaner cleaner_;
    std::vector<std::string> instances_;  // "nodes[i]: meshes[m].primitives[p]" per append()
    std::vector<uint32_t> kept_;          // scratch
    std::vector<FaceCleaner::Pending> zeroArea_;
    bool hardEdges_;  // InputOptions::hardEdges
    HardEdges hard_;  // the base faces' corner normals, with hardEdges_

    std::string defect(FaceCleaner::Fate fate) const {
        return cleaner_.defect(fate, [&](uint64_t tag) { return triangle(tag); });
    }

    // Drops the zero-area triangles cleaning decides against (mesh_clean.h); their
    // vertices stay, unused, where no other triangle has them.
    Status settleZeroArea() {
        const std::vector<size_t> gone = cleaner_.settleZeroArea(mesh_, zeroArea_);
        if (gone.empty()) return Status::ok();
        if (cleaning_ == InputCleaning::Refuse)
            return badInput(name_ + ": " + triangle(zeroArea_[gone[0]].tag), defect(FaceCleaner::Fate::ZeroArea));
        std::vector<uint8_t> drop(mesh_.faceCount(), 0);
        for (size_t i : gone) drop[zeroArea_[i].first] = 1;
        eraseTriangles(mesh_, drop);
        if (hardEdges_) hard_.erase(drop);
        return Status::ok();
    }

    // A cleaner's tag: instance << 32 | triangle.
    std::string triangle(uint64_t tag) const {
        return instances_[size_t(tag >> 32)] + " triangle " + str(uint32_t(tag));
    }

    // Checks the node hierarchy and picks the scene's root nodes.
    Status sceneRoots(std::vector<int>& roots) {
        const size_t n = model_.nodes.size();
        std::vector<int> parent;
        if (Status st = nodeParents(model_, name_, parent); !st) return st;
        if (model_.scenes.empty()) {
            for (size_t i = 0; i < n; ++i)
                if (parent[i] < 0) roots.push_back(int(i));
            return Status::ok();
        }
        const int s = model_.defaultScene >= 0 ? model_.defaultScene : 0;
        if (size_t(s) >= model_.scenes.size())
            return badInput(name_, "scene " + str(s) + " does not exist (" + str(model_.scenes.size()) + " scenes)");
        // A scene must list root nodes only. Exporters sometimes list a child too:
        // its tree is drawn instead, once, so the child keeps its parents'
        // transforms and is not drawn twice.
        roots.clear();
        for (int r : model_.scenes[size_t(s)].nodes) {
            const std::string where = name_ + ": scenes[" + str(s) + "].nodes";
            if (r < 0 || size_t(r) >= n) return badInput(where, "node " + str(r) + " does not exist");
            int root = r;
            while (parent[size_t(root)] >= 0) root = parent[size_t(root)];
            if (root != r)
                mesh_.warnings.push_back(where + ": nodes[" + str(r) + "] is not a root (its parent is nodes[" +
                                         str(parent[size_t(r)]) + "]); drawn once, in the tree of nodes[" + str(root) +
                                         "]");
            if (std::find(roots.begin(), roots.end(), root) == roots.end()) roots.push_back(root);
        }
        return Status::ok();
    }

    // Appends every TRIANGLES primitive of mesh `index`, transformed by `world`.
    Status instance(int index, const Matrix& world, const std::string& where) {
        if (index < 0 || size_t(index) >= meshes_.size())
            return badInput(where, "mesh " + str(index) + " does not exist (" + str(meshes_.size()) + " meshes)");
        Status st;
        if (!loaded_[size_t(index)]++) st = loadMesh(index);
        const bool flip = determinant3(world) < 0;
        for (const Primitive& prim : meshes_[size_t(index)])
            if (st) st = append(prim, world, flip, where);
        return st;
    }

    Status loadMesh(int m) {
        const auto& prims = model_.meshes[size_t(m)].primitives;
        for (size_t i = 0; i < prims.size(); ++i) {
            const tinygltf::Primitive& p = prims[i];
            const std::string where = name_ + ": meshes[" + str(m) + "].primitives[" + str(i) + "]";
            if (!isTriangles(p)) {
                mesh_.warnings.push_back(where + ": mode " + str(p.mode) + " is not TRIANGLES (4); skipped");
                continue;
            }
            Primitive prim;
            prim.where = "meshes[" + str(m) + "].primitives[" + str(i) + "]";
            Status st = readPrimitive(model_, p, quantized_, hardEdges_, where, budget_, prim);
            if (!st) return st;
            meshes_[size_t(m)].push_back(std::move(prim));
        }
        return Status::ok();
    }

    // Welds the corners of `prim` under `world` into the control mesh.
    Status append(const Primitive& prim, const Matrix& world, bool flip, const std::string& where) {
        const size_t triangles = prim.triangles.size() / 3;
        const Limits& limits = budget_.limits();
        if (mesh_.faces.size() / 3 + triangles > limits.maxFaces)
            return badInput(where, "the scene has " +
                                       limitMessage("at least " + str(mesh_.faces.size() / 3 + triangles),
                                                    "triangles (instances included)", limits.maxFaces, "--max-faces"));
        const bool uvs = !prim.uvs.empty();
        uvsComplete_ = uvsComplete_ && uvs;
        anyUVs_ = anyUVs_ || uvs;
        static const int kOrder[2][3] = {{0, 1, 2}, {0, 2, 1}};
        const int* order = kOrder[flip ? 1 : 0];
        const Matrix& m = world;
        const std::array<double, 9> nm = normalMatrix(world);
        const bool normals = hardEdges_ && !prim.normals.empty();
        const uint64_t instance = instances_.size();
        instances_.push_back(where.substr(name_.size() + 2) + ": " + prim.where);
        for (size_t t = 0; t < triangles; ++t) {
            float xyz[3][3];
            Key keys[3];
            for (int k = 0; k < 3; ++k) {
                const double* p = &prim.positions[3 * size_t(prim.triangles[3 * t + size_t(order[k])])];
                for (int r = 0; r < 3; ++r)
                    xyz[k][r] = float(m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r]);
                keys[k] = Key{weldBits(xyz[k][0]), weldBits(xyz[k][1]), weldBits(xyz[k][2])};
            }
            if (keys[0] == keys[1] || keys[1] == keys[2] || keys[2] == keys[0]) {
                if (collapsed_++ == 0) firstCollapsed_ = where + ": " + prim.where + " triangle " + str(t);
                continue;
            }
            uint32_t ids[3];
            for (int k = 0; k < 3; ++k) {
                const auto [it, added] = weld_.try_emplace(keys[k], uint32_t(weld_.size()));
                ids[k] = it->second;
                if (added) mesh_.positions.insert(mesh_.positions.end(), xyz[k], xyz[k] + 3);
            }
            const uint64_t tag = instance << 32 | uint32_t(t);
            const auto fate = cleaner_.clean(ids, 3, tag, kept_);
            if (fate == FaceCleaner::Fate::ZeroArea)
                zeroArea_.push_back({tag, uint32_t(mesh_.faces.size() / 3), 1});
            else if (fate != FaceCleaner::Fate::Kept) {  // a duplicate: the face it repeats has its vertices
                if (cleaning_ == InputCleaning::Refuse) return badInput(name_ + ": " + triangle(tag), defect(fate));
                continue;
            }
            if (weld_.size() > limits.maxVertices)
                return badInput(where,
                                "the scene has " + limitMessage("at least " + str(weld_.size()), "distinct vertices",
                                                                limits.maxVertices, "--max-vertices"));
            double n[3][3] = {};
            for (int k = 0; k < 3; ++k) {
                const uint32_t v = prim.triangles[3 * t + size_t(order[k])];
                for (int r = 0; normals && r < 3; ++r)
                    n[k][r] = nm[r] * prim.normals[3 * size_t(v)] + nm[3 + r] * prim.normals[3 * size_t(v) + 1] +
                              nm[6 + r] * prim.normals[3 * size_t(v) + 2];
                mesh_.faces.push_back(ids[k]);
                if (uvsComplete_) {
                    mesh_.faceUVs.push_back(float(prim.uvs[2 * size_t(v)]));
                    mesh_.faceUVs.push_back(float(prim.uvs[2 * size_t(v) + 1]));
                }
            }
            if (hardEdges_) hard_.addFace(normals ? n[0] : nullptr, normals ? n[1] : nullptr, normals ? n[2] : nullptr);
        }
        return Status::ok();
    }
};

}  // namespace

Status parseGltf(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir,
                 InputMesh& mesh) {
    return parseGltf(data, size, name, baseDir, Limits{}, mesh);
}

Status parseGltf(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir,
                 const Limits& limits, InputMesh& mesh) {
    InputOptions options;
    options.limits = limits;
    return parseGltf(data, size, name, baseDir, options, mesh);
}

Status parseGltf(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir,
                 const InputOptions& options, InputMesh& mesh) {
    const Limits& limits = options.limits;
    InputMesh result;
    Status st;
    try {
        tinygltf::Model model;
        st = gltf::loadModel(data, size, name, baseDir, limits, model, result.warnings);
        if (st) st = Reader(model, name, options, result).run();
        if (options.boundary) result.boundary = *options.boundary;
    } catch (const std::bad_alloc&) {
        st = Status::error(Status::Internal, name + ": out of memory");
    } catch (const std::exception& e) {
        st = Status::error(Status::BadInput, name + ": " + shortenQuotes(e.what()));
    } catch (...) { st = Status::error(Status::Internal, name + ": unknown exception"); }
    if (st) {
        mesh = std::move(result);
    } else {
        mesh = InputMesh{};
        mesh.warnings = std::move(result.warnings);
    }
    return st;
}

}  // namespace lt
