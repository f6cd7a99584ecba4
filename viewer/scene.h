// looprender's scene: what a baked glTF scene holds beside its surfaces (nodes,
// cameras, materials, textures, animations, skins), read from the GLB, and the
// pose of it at a time. This is what an engine does with a baked asset, written
// as a client of looptess's public API (asset.h, vulkan.h); the library itself
// knows nothing of nodes or materials.
//
// Pure CPU code without I/O: tests and fuzzers call it on bytes.
//
// What is kept and what is not (looprender --help says the same):
//   nodes        hierarchy, TRS or matrix, of the scene `scene` (else scenes[0],
//                else every root node)
//   cameras      the first node with a perspective camera (orthographic: ignored)
//   materials    pbrMetallicRoughness factors and base colour and metallic-
//                roughness textures, normal, occlusion and emissive textures, each
//                on TEXCOORD_0 or TEXCOORD_1, alphaMode MASK (cut-off) and
//                doubleSided; BLEND is drawn opaque, KHR_texture_transform and
//                other material extensions are not applied
//   images       PNG and JPEG in a bufferView (loopbake embeds every image so);
//                others (KTX2, WebP, URIs) are drawn white, with a warning
//   animations   one at a time: translation, rotation, scale; LINEAR, STEP,
//                CUBICSPLINE
//   skins        JOINTS_n / WEIGHTS_n of the cage primitives, carried over to the
//                control vertices (the first copy of a welded vertex)
//   morphs       POSITION targets of the cage primitives, carried over to the control
//                vertices; weights from animations, the node or the mesh
//   not applied  sparse accessors in animations, skins and targets (an error),
//                lights (one fixed light)
#pragma once

#include "looptess/asset.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace looprender {

using Mat4 = std::array<float, 16>;  // column-major, as glTF

struct SceneNode {
    std::vector<uint32_t> children;
    int mesh = -1, skin = -1, camera = -1;
    bool hasMatrix = false;
    Mat4 matrix{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    float translation[3] = {0, 0, 0}, rotation[4] = {0, 0, 0, 1}, scale[3] = {1, 1, 1};
    std::vector<float> weights;  // morph target weights (empty: the mesh's)
};

struct TextureRef {
    int image = -1;         // index into Scene::images; -1: no texture
    int sampler = -1;       // index into Scene::samplers; -1: glTF's default
    uint32_t texCoord = 0;  // 0 or 1
};

struct SceneMaterial {
    float baseColor[4] = {1, 1, 1, 1};
    float metallic = 1, roughness = 1;
    float emissive[3] = {0, 0, 0};
    float normalScale = 1, occlusionStrength = 1;
    float alphaCutoff = 0.5f;
    bool mask = false;  // alphaMode MASK
    bool doubleSided = false;
    TextureRef baseColorTexture, metallicRoughnessTexture, normalTexture, occlusionTexture, emissiveTexture;
};

struct SceneSampler {
    int magFilter = 9729, minFilter = 9987;  // LINEAR, LINEAR_MIPMAP_LINEAR
    int wrapS = 10497, wrapT = 10497;        // REPEAT
};

struct SceneImage {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba;  // decoded, top row first; empty: could not decode (drawn white)
};

struct AnimationChannel {
    uint32_t animation = 0;  // index into the file's animations
    uint32_t node = 0;
    enum Path { Translation, Rotation, Scale, Weights } path = Translation;
    enum Interpolation { Linear, Step, CubicSpline } interpolation = Linear;
    std::vector<float> times;   // ascending
    std::vector<float> values;  // components per key, x3 for CUBICSPLINE (in, value, out)
    uint32_t components = 3;    // 3 (translation, scale), 4 (rotation), the mesh's targets (weights)
};

struct SceneSkin {
    std::vector<uint32_t> joints;   // nodes
    std::vector<Mat4> inverseBind;  // per joint (identity when absent)
};

// Per control vertex of a surface: up to 8 joint influences (JOINTS_0/1).
struct SkinWeights {
    uint32_t sets = 0;             // 4 influences per set
    std::vector<uint32_t> joints;  // 4 * sets per control vertex
    std::vector<float> weights;
};

struct SceneMesh {
    int surface = -1;            // index into Scene::surfaces; -1: not subdivided (not drawn)
    std::vector<int> materials;  // per cage primitive (-1: the default material)
    SkinWeights skin;            // empty when the cage has no JOINTS_0
    // Morph targets' POSITION displacements per control vertex (3 floats each; the
    // first copy of a welded vertex gives them), and the mesh's default weights.
    std::vector<std::vector<float>> targets;
    std::vector<float> weights;
};

struct Scene {
    std::vector<lt::SceneSurface> surfaces;  // readSceneGlb's, in mesh order
    std::vector<SceneMesh> meshes;           // per glTF mesh
    std::vector<SceneNode> nodes;
    std::vector<uint32_t> roots;  // the drawn scene's root nodes
    struct Camera {
        float yfov = 0.7f, znear = 0.01f, zfar = 0;  // zfar 0: infinite
    };
    std::vector<Camera> cameras;
    std::vector<SceneMaterial> materials;
    std::vector<SceneSampler> samplers;
    std::vector<SceneImage> images;
    std::vector<TextureRef> textures;        // per glTF texture: its image and sampler
    std::vector<AnimationChannel> channels;  // of every animation
    std::vector<std::string> animations;     // names ("" where none), per animation
    std::vector<SceneSkin> skins;
    std::vector<std::string> warnings;  // what is drawn differently from the file
};

// Reads a GLB with looptess surfaces (readSceneGlb) and the scene around them.
// Safe on untrusted bytes: errors (Status::BadInput) name `name` and the glTF object.
lt::Status loadScene(const uint8_t* data, size_t size, const std::string& name, Scene& out);

// One drawn surface at a time: a node with a subdivided mesh.
struct SceneInstance {
    uint32_t node = 0, mesh = 0;
    Mat4 model;  // object to world (identity for a skinned node)
    // Morphed and skinned control points (skinned: world space), or empty: the asset's.
    std::vector<float> controlPoints;
    // What posed them (the GPU's posing, scene_skin.h, takes the same): a weight per
    // morph target of the mesh, and for a skinned node its joints' J_i * IBM_i.
    std::vector<float> morphWeights;
    std::vector<Mat4> joints;
};

// The control points `rest` of `mesh` morphed (p + w_t d_t for each target with w_t
// != 0, in order) and, with `joints` (else left out), skinned: p' = M (p, 1) with
// M = sum_i w_i J_i over the vertex's influences with w_i != 0, times 1 / sum w_i
// when the weights do not sum to 1 (identity when they are all 0). In this operation
// order, every product and sum rounded once (shaders/skin.comp follows it, bit for
// bit): M's elements accumulate influence by influence; (x, y, z) = (M0 x + M1 y) +
// (M2 z + M3), per component, Mk the columns.
std::vector<float> poseControlPoints(const std::vector<float>& rest, const SceneMesh& mesh,
                                     const std::vector<float>& morphWeights, const std::vector<Mat4>& joints);

struct ScenePose {
    std::vector<Mat4> world;  // per node
    std::vector<SceneInstance> instances;
    int cameraNode = -1;  // the first node (depth first) with a camera
};

// Poses the scene with animation `animation` at `time` seconds (clamped to its
// keys; -1 or no such animation: the file's rest pose), morphs the control points
// by the instance's target weights (animated, else the node's, else the mesh's),
// then skins them, on the CPU. Nodes are visited depth first from the roots, in
// order.
ScenePose poseScene(const Scene& scene, int animation, float time);

// Matrix helpers (column-major).
Mat4 multiply(const Mat4& a, const Mat4& b);
void transformPoint(const Mat4& m, const float p[3], float out[3]);

}  // namespace looprender
