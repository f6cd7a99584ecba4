// looprender: a scene's pose at a time (see scene.h). glTF 2.0 spec, "Animations",
// "Morph Targets" and "Skins": a node's local matrix is T * R * S (or its `matrix`),
// animated channels replacing T, R or S (or the morph weights); a morphed vertex is
// v + sum_t w_t d_t; a skinned vertex is sum_i w_i * (J_i * IBM_i) * v,
// where J_i is joint i's world matrix, and the skinned node's own transform is
// ignored. The cage is skinned; the tables then give the limit surface of the
// skinned cage, exactly (subdivision is linear in the control points).
#define GLM_FORCE_DEPTH_ZERO_TO_ONE
#include "scene.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>

namespace looprender {
namespace {

glm::mat4 toGlm(const Mat4& m) { return glm::make_mat4(m.data()); }
Mat4 fromGlm(const glm::mat4& m) {
    Mat4 out;
    std::copy(glm::value_ptr(m), glm::value_ptr(m) + 16, out.begin());
    return out;
}

// Samples `ch` at `time` into out[comps] (glTF spec, Appendix C).
void sample(const AnimationChannel& ch, float time, float* out) {
    const size_t comps = ch.components;
    const bool cubic = ch.interpolation == AnimationChannel::CubicSpline;
    const size_t stride = comps * (cubic ? 3 : 1), valueAt = cubic ? comps : 0;
    auto value = [&](size_t key, size_t part) { return &ch.values[key * stride + part]; };
    const size_t n = ch.times.size();
    if (time <= ch.times[0] || n == 1) return (void)std::copy_n(value(0, valueAt), comps, out);
    if (time >= ch.times[n - 1]) return (void)std::copy_n(value(n - 1, valueAt), comps, out);
    const size_t k = size_t(std::upper_bound(ch.times.begin(), ch.times.end(), time) - ch.times.begin()) - 1;
    const float dt = ch.times[k + 1] - ch.times[k], t = (time - ch.times[k]) / dt;
    if (ch.interpolation == AnimationChannel::Step) return (void)std::copy_n(value(k, valueAt), comps, out);
    if (cubic) {  // Hermite: value, out-tangent of key k; in-tangent, value of key k + 1
        const float t2 = t * t, t3 = t2 * t;
        const float h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
        for (size_t c = 0; c < comps; ++c)
            out[c] = h00 * value(k, comps)[c] + h10 * dt * value(k, 2 * comps)[c] + h01 * value(k + 1, comps)[c] +
                     h11 * dt * value(k + 1, 0)[c];
    } else if (ch.path == AnimationChannel::Rotation) {
        const float* a = value(k, 0);
        const float* b = value(k + 1, 0);
        glm::quat q = glm::slerp(glm::quat(a[3], a[0], a[1], a[2]), glm::quat(b[3], b[0], b[1], b[2]), t);
        out[0] = q.x, out[1] = q.y, out[2] = q.z, out[3] = q.w;
    } else {
        for (size_t c = 0; c < comps; ++c) out[c] = value(k, 0)[c] * (1 - t) + value(k + 1, 0)[c] * t;
    }
    if (ch.path == AnimationChannel::Rotation) {  // cubic and linear rotations: unit quaternions
        float len = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] + out[3] * out[3]);
        if (len > 0)
            for (size_t c = 0; c < 4; ++c) out[c] /= len;
    }
}

glm::mat4 localMatrix(const SceneNode& node) {
    if (node.hasMatrix) return toGlm(node.matrix);
    const float* r = node.rotation;
    glm::mat4 t =
        glm::translate(glm::mat4(1), glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
    glm::mat4 rot = glm::mat4_cast(glm::quat(r[3], r[0], r[1], r[2]));
    glm::mat4 s = glm::scale(glm::mat4(1), glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
    return t * rot * s;
}

}  // namespace

std::vector<float> poseControlPoints(const std::vector<float>& rest, const SceneMesh& mesh,
                                     const std::vector<float>& morphWeights, const std::vector<Mat4>& joints) {
    std::vector<float> out = rest;
    for (size_t t = 0; t < mesh.targets.size() && t < morphWeights.size(); ++t) {
        const float w = morphWeights[t];
        if (w == 0) continue;
        for (size_t i = 0; i < out.size(); ++i) out[i] = out[i] + w * mesh.targets[t][i];
    }
    if (joints.empty()) return out;
    const SkinWeights& sw = mesh.skin;
    const size_t influences = 4 * sw.sets;
    for (size_t v = 0; v < out.size() / 3; ++v) {
        float m[16] = {}, total = 0;
        for (size_t i = 0; i < influences; ++i) {
            const float w = sw.weights[v * influences + i];
            if (w == 0) continue;
            const Mat4& j = joints[sw.joints[v * influences + i]];
            for (int e = 0; e < 16; ++e) m[e] = m[e] + w * j[size_t(e)];
            total = total + w;
        }
        // Weights should sum to 1 (glTF); files that break it (RobotExpressive) are
        // drawn normalized, as three.js draws them. An unweighted vertex stays put.
        if (total == 0) {
            for (int e = 0; e < 16; ++e) m[e] = e % 5 == 0 ? 1.0f : 0.0f;
        } else if (total != 1.0f) {
            const float scale = 1.0f / total;
            for (float& e : m) e = e * scale;
        }
        const float x = out[3 * v], y = out[3 * v + 1], z = out[3 * v + 2];
        for (int c = 0; c < 3; ++c) out[3 * v + size_t(c)] = (m[c] * x + m[4 + c] * y) + (m[8 + c] * z + m[12 + c]);
    }
    return out;
}

Mat4 multiply(const Mat4& a, const Mat4& b) { return fromGlm(toGlm(a) * toGlm(b)); }

void transformPoint(const Mat4& m, const float p[3], float out[3]) {
    glm::vec4 q = toGlm(m) * glm::vec4(p[0], p[1], p[2], 1.0f);
    out[0] = q.x, out[1] = q.y, out[2] = q.z;
}

ScenePose poseScene(const Scene& scene, int animation, float time) {
    std::vector<SceneNode> nodes = scene.nodes;
    for (const AnimationChannel& ch : scene.channels) {
        if (int(ch.animation) != animation) continue;
        SceneNode& node = nodes[ch.node];
        std::vector<float> v(ch.components);
        sample(ch, time, v.data());
        if (ch.path == AnimationChannel::Weights) {
            node.weights = v;
            continue;
        }
        float* dst = ch.path == AnimationChannel::Translation ? node.translation
                     : ch.path == AnimationChannel::Rotation  ? node.rotation
                                                              : node.scale;
        std::copy(v.begin(), v.end(), dst);
        node.hasMatrix = false;  // glTF: animated nodes have TRS
    }
    ScenePose pose;
    pose.world.assign(nodes.size(), Mat4{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
    // Depth first from the roots, in order (loadScene checked the hierarchy is a forest).
    std::vector<std::pair<uint32_t, glm::mat4>> stack;
    for (auto r = scene.roots.rbegin(); r != scene.roots.rend(); ++r) stack.push_back({*r, glm::mat4(1)});
    std::vector<uint32_t> order;
    while (!stack.empty()) {
        auto [n, parent] = stack.back();
        stack.pop_back();
        glm::mat4 world = parent * localMatrix(nodes[n]);
        pose.world[n] = fromGlm(world);
        order.push_back(n);
        if (pose.cameraNode < 0 && nodes[n].camera >= 0) pose.cameraNode = int(n);
        for (auto c = nodes[n].children.rbegin(); c != nodes[n].children.rend(); ++c) stack.push_back({*c, world});
    }
    // Instances after every world matrix is known (joints may lie anywhere in the tree).
    for (uint32_t n : order) {
        const SceneNode& node = nodes[n];
        if (node.mesh < 0 || scene.meshes[size_t(node.mesh)].surface < 0) continue;
        const SceneMesh& mesh = scene.meshes[size_t(node.mesh)];
        SceneInstance inst;
        inst.node = n;
        inst.mesh = uint32_t(node.mesh);
        inst.model = pose.world[n];
        const std::vector<float>& rest = scene.surfaces[size_t(mesh.surface)].asset.positions;
        const std::vector<float>& weights = node.weights.size() == mesh.targets.size() ? node.weights : mesh.weights;
        const bool morphed = std::any_of(weights.begin(), weights.end(), [](float w) { return w != 0; });
        if (morphed) inst.morphWeights = weights;
        if (node.skin >= 0 && mesh.skin.sets > 0) {
            const SceneSkin& skin = scene.skins[size_t(node.skin)];
            for (size_t j = 0; j < skin.joints.size(); ++j)
                inst.joints.push_back(fromGlm(toGlm(pose.world[skin.joints[j]]) * toGlm(skin.inverseBind[j])));
            inst.model = Mat4{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
        }
        if (morphed || !inst.joints.empty())
            inst.controlPoints = poseControlPoints(rest, mesh, inst.morphWeights, inst.joints);
        pose.instances.push_back(std::move(inst));
    }
    return pose;
}

}  // namespace looprender
