// looprender: output files, report fields and the camera (see looprender_common.h).
#include "looprender_common.h"

#include "looptess/tools/file_io.h"

#define GLM_FORCE_DEPTH_ZERO_TO_ONE
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace looprender {

std::vector<float> scaledEditValues(const Options& o, const lt::Asset& asset) {
    std::vector<float> values = lt::bakedEditValues(asset);
    for (float& v : values) v = v * o.editScale;
    return values;
}

namespace {
lt::DrawPath namedPath(const std::string& name) {
    return name == "tessellator" ? lt::DrawPath::Tessellator
           : name == "patterns"  ? lt::DrawPath::Patterns
           : name == "compute"   ? lt::DrawPath::Compute
                                 : lt::DrawPath::Auto;
}
}  // namespace

lt::DrawPath choosePath(const Options& o, bool tessellation, bool screenPatterns) {
    if (o.path != "auto") return namedPath(o.path);
    if (o.spacing != lt::Spacing::Equal) return lt::DrawPath::Tessellator;
    // Screen-space patterns are slower than the tessellator on lavapipe (bench/README.md,
    // "Screen-space factors on the pattern path"): only where there is no tessellator.
    if (o.lod == lt::LodMode::Screen)
        return !tessellation && screenPatterns ? lt::DrawPath::Patterns : lt::DrawPath::Tessellator;
    return lt::DrawPath::Patterns;
}

lt::DrawPath framePath(const Options& o, lt::DrawPath single) {
    return o.path == "auto" && o.frames < 2 ? single : namedPath(o.path);
}

const char* pathName(lt::DrawPath path) {
    const char* names[4] = {"tessellator", "patterns", "compute", "auto"};
    return names[size_t(path)];
}

int fail(const lt::Status& st) {
    std::fprintf(stderr, "looprender: error: %s\n", st.message.c_str());
    return int(st.code);
}

lt::Status writePlyFile(const std::string& path, const lt::Tessellation& soup) {
    std::vector<uint8_t> ply;
    writePly(soup, ply);
    return lt::writeFileAtomic(path, ply.data(), ply.size());
}

size_t meshPlyLayout(size_t vertices, size_t triangles, bool texcoords, std::vector<uint8_t>& bytes) {
    const std::string header =
        "ply\nformat binary_little_endian 1.0\ncomment looptess indexed surface\n"
        "element vertex " +
        std::to_string(vertices) +
        "\nproperty float x\nproperty float y\nproperty float z\n"
        "property float nx\nproperty float ny\nproperty float nz\n" +
        std::string(texcoords ? "property float tx\nproperty float ty\nproperty float tz\n"
                                "property float tw\nproperty float s\nproperty float t\n"
                              : "") +
        "element face " + std::to_string(triangles) + "\nproperty list uchar uint vertex_indices\nend_header\n";
    bytes.resize(header.size() + vertices * meshPlyFloats(texcoords) * 4 + triangles * 13);
    std::copy(header.begin(), header.end(), bytes.begin());
    return header.size();
}

void putMeshFaces(const std::vector<uint32_t>& indices, std::vector<uint8_t>& bytes) {
    const size_t triangles = indices.size() / 3;
    uint8_t* at = bytes.data() + bytes.size() - 13 * triangles;
    for (size_t t = 0; t < triangles; ++t, at += 13) {  // little-endian hosts only, as writePly
        at[0] = 3;
        std::memcpy(at + 1, &indices[3 * t], 12);
    }
}

lt::Status writeMeshFile(const std::string& path, const Mesh& mesh) {
    const size_t vertices = mesh.vertices.size() / kMeshFloats, floats = meshPlyFloats(mesh.texcoords);
    std::vector<uint8_t> bytes;
    const size_t first = meshPlyLayout(vertices, mesh.indices.size() / 3, mesh.texcoords, bytes);
    uint8_t* at = bytes.data() + first;
    for (size_t v = 0; v < vertices; ++v) std::memcpy(at + v * floats * 4, &mesh.vertices[v * kMeshFloats], floats * 4);
    putMeshFaces(mesh.indices, bytes);
    return lt::writeFileAtomic(path, bytes.data(), bytes.size());
}

nlohmann::json meshReport(size_t vertices, size_t triangles) {
    return {{"vertices", vertices}, {"triangles", triangles}, {"drawPath", "patterns"}};
}

void printMesh(const Options& o, size_t vertices, size_t triangles, const std::string& where) {
    std::printf("%s: %zu vertices, %zu triangles, indexed (%s)\n", o.mesh.c_str(), vertices, triangles, where.c_str());
}

lt::Status writeJsonFile(const std::string& path, const nlohmann::json& report) {
    std::string text = report.dump(2) + "\n";
    return lt::writeFileAtomic(path, reinterpret_cast<const uint8_t*>(text.data()), text.size());
}

nlohmann::json baseReport(const Options& o, const lt::Asset& asset, float tessFactor, uint32_t depth,
                          uint64_t triangles, lt::DrawPath path) {
    static const char* kLod[3] = {"global", "distance", "screen"};
    return {{"input", o.input},
            {"path", o.cpu ? "cpu" : "vulkan"},
            {"lod", kLod[int(o.lod)]},
            {"pixelsPerEdge", o.pixelsPerEdge},
            {"tessFactor", tessFactor},
            {"spacing", o.spacing == lt::Spacing::Equal ? "equal" : "fractional_odd"},
            {"drawPath", pathName(path)},
            {"watertight", o.watertight},
            {"displaced", o.displace && asset.displacement.present()},
            {"depth", depth},
            {"maxDepth", asset.maxDepth()},
            {"baseFaces", asset.faceCount()},
            {"triangles", triangles},
            {"vertices", triangles * 3}};
}

namespace {

struct Camera {
    glm::vec3 eye, target;
    float fov = 0;     // vertical, radians
    float radius = 0;  // of the bounding box
};

// o's camera, or one framing the control mesh's bounding box.
Camera camera(const Options& o, const lt::Asset& asset) {
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (size_t i = 0; i + 2 < asset.positions.size(); i += 3) {
        glm::vec3 p(asset.positions[i], asset.positions[i + 1], asset.positions[i + 2]);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    glm::vec3 centre = (lo + hi) * 0.5f;
    Camera c;
    c.radius = std::max(glm::length(hi - lo) * 0.5f, 1e-6f);
    c.fov = glm::radians(o.camera ? o.fovDegrees : 40.0f);
    if (o.camera) {
        c.eye = glm::vec3(o.eye[0], o.eye[1], o.eye[2]);
        c.target = glm::vec3(o.target[0], o.target[1], o.target[2]);
    } else {  // three-quarter view from the front right, y up (glTF's convention)
        c.target = centre;
        c.eye = centre + glm::normalize(glm::vec3(0.6f, 0.35f, 1.0f)) * (c.radius / std::sin(c.fov * 0.5f) * 0.9f);
    }
    return c;
}

}  // namespace

lt::EvalSettings evalSettings(const Options& o, lt::DrawPath path) {
    lt::EvalSettings es;
    es.tessFactor = o.tess;
    es.spacing = o.spacing;
    es.path = path;
    es.watertight = o.watertight;
    es.displace = o.displace;
    es.threads = o.threads;
    return es;
}

lt::Lod lodSettings(const Options& o, const lt::Asset& asset) {
    Camera c = camera(o, asset);
    float eye[3] = {c.eye.x, c.eye.y, c.eye.z};
    return lt::cameraLod(o.lod, eye, glm::degrees(c.fov), o.height, o.pixelsPerEdge);
}

void cameraMatrix(const Options& o, const lt::Asset& asset, float mvp[16], float light[3]) {
    Camera c = camera(o, asset);
    const glm::vec3 &eye = c.eye, &target = c.target;
    float radius = c.radius, fov = c.fov;
    float distance = std::max(glm::length(eye - target), 1e-6f);
    float aspect = float(o.width) / float(o.height);
    glm::vec3 up = std::fabs(glm::normalize(eye - target).y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    glm::mat4 view = glm::lookAt(eye, target, up);
    float nearPlane = std::max(distance - radius * 1.5f, distance * 1e-3f), farPlane = distance + radius * 1.5f;
    glm::mat4 projection = glm::perspective(fov, aspect, nearPlane, farPlane);
    projection[1][1] *= -1.0f;  // Vulkan's clip space has y down
    glm::mat4 m = projection * view;
    std::copy(glm::value_ptr(m), glm::value_ptr(m) + 16, mvp);
    glm::vec3 towardsEye = glm::normalize(eye - target);
    light[0] = towardsEye.x;
    light[1] = towardsEye.y;
    light[2] = towardsEye.z;
}

lt::Status writePngFile(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba) {
    std::vector<uint8_t> png;
    auto sink = [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<uint8_t>*>(context);
        out->insert(out->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
    };
    if (!stbi_write_png_to_func(sink, &png, int(width), int(height), 4, rgba.data(), int(width * 4)))
        return lt::Status::error(lt::Status::Internal, "PNG encoding failed");
    return lt::writeFileAtomic(path, png.data(), png.size());
}

}  // namespace looprender
