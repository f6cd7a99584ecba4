// baker/src/gltf_draco.cpp -- lt::gltf::decodeDraco. See gltf_draco.h.
#include "gltf_draco.h"

#include <draco/compression/decode.h>
#include <draco/compression/point_cloud/point_cloud_decoder.h>
#include <draco/core/varint_decoding.h>
#include <draco/metadata/geometry_metadata.h>
#include <draco/metadata/metadata_decoder.h>

namespace lt::gltf {
namespace {

template <class T>
std::string str(T v) {
    return std::to_string(v);
}

// Reads the triangle and vertex counts the decoder will allocate by, the way Draco
// 1.5.5 reads them (point_cloud_decoder.cc, mesh_sequential_decoder.cc,
// mesh_edgebreaker_decoder{,_impl}.cc), and returns why they are refused, or "".
std::string countProblem(const uint8_t* data, size_t size, DecodeBudget& budget) {
    draco::DecoderBuffer buf;
    buf.Init(reinterpret_cast<const char*>(data), size);
    draco::DracoHeader h;
    if (!draco::PointCloudDecoder::DecodeHeader(&buf, &h).ok()) return "not a Draco bitstream";
    if (h.encoder_type != draco::TRIANGULAR_MESH) return "the Draco payload is not a triangle mesh";
    const uint16_t version = DRACO_BITSTREAM_VERSION(h.version_major, h.version_minor);
    if (version < DRACO_BITSTREAM_VERSION(2, 0) || version > DRACO_BITSTREAM_VERSION(2, 2))
        return "Draco bitstream version " + str(int(h.version_major)) + "." + str(int(h.version_minor)) +
               " is not supported (2.0 to 2.2)";
    buf.set_bitstream_version(version);
    if (h.flags & METADATA_FLAG_MASK) {
        draco::GeometryMetadata metadata;
        if (!draco::MetadataDecoder().DecodeGeometryMetadata(&buf, &metadata)) return "malformed Draco metadata";
    }
    const bool v22 = version >= DRACO_BITSTREAM_VERSION(2, 2);
    uint32_t faces = 0, vertices = 0, newVertices = 0;
    bool ok = false;
    if (h.encoder_method == draco::MESH_SEQUENTIAL_ENCODING) {
        ok = v22 ? draco::DecodeVarint(&faces, &buf) && draco::DecodeVarint(&vertices, &buf)
                 : buf.Decode(&faces) && buf.Decode(&vertices);
    } else if (h.encoder_method == draco::MESH_EDGEBREAKER_ENCODING) {
        uint8_t traversal;
        ok = buf.Decode(&traversal) && (v22 || draco::DecodeVarint(&newVertices, &buf)) &&
             draco::DecodeVarint(&vertices, &buf) && draco::DecodeVarint(&faces, &buf);
    } else {
        return "unknown Draco encoding method " + str(int(h.encoder_method));
    }
    if (!ok) return "truncated Draco connectivity header";
    if (faces > budget.maxTriangles() || vertices > budget.maxElements() || newVertices > budget.maxElements())
        return "the Draco mesh declares " + str(faces) + " triangles and " + str(vertices) +
               " vertices, more than the limit of " + str(budget.maxTriangles()) +
               " faces (and 3 vertices per face; raise it with --max-faces)";
    if (!budget.take(uint64_t(vertices) + newVertices + 3 * uint64_t(faces))) return budget.exhausted();
    return "";
}

// The attribute with unique id `id`, which must have `components` numeric components.
const draco::PointAttribute* attribute(const draco::Mesh& mesh, int id, int components, const std::string& what,
                                       const std::string& where, Status& st) {
    const draco::PointAttribute* a = id >= 0 ? mesh.GetAttributeByUniqueId(uint32_t(id)) : nullptr;
    if (!a)
        st = badInput(where, "attributes." + what + ": no attribute with id " + str(id) + " in the Draco payload");
    else if (a->num_components() != components)
        st = badInput(where, "attributes." + what + ": Draco attribute has " + str(int(a->num_components())) +
                                 " components, expected " + str(components));
    else if (a->data_type() == draco::DT_BOOL || a->data_type() == draco::DT_INVALID)
        // Converting a decoded bool that is neither 0 nor 1 is undefined behaviour in Draco.
        st = badInput(where, "attributes." + what + ": Draco attribute is not numeric");
    return st ? a : nullptr;
}

// Converts every point's value of `a` to double, `components` per point.
Status readPoints(const draco::PointAttribute& a, uint32_t points, int components, const std::string& what,
                  const std::string& where, std::vector<double>& out) {
    out.resize(size_t(points) * components);
    for (uint32_t p = 0; p < points; ++p) {
        const draco::AttributeValueIndex v = a.mapped_index(draco::PointIndex(p));
        if (v.value() >= a.size() || !a.ConvertValue<double>(v, int8_t(components), &out[size_t(p) * components]))
            return badInput(where, "attributes." + what + ": Draco value of point " + str(p) + " cannot be read");
    }
    return Status::ok();
}

}  // namespace

Status decodeDraco(const uint8_t* data, size_t size, int positionId, int texcoordId, int normalId,
                   const std::string& where, DecodeBudget& budget, Primitive& out) {
    const std::string problem = countProblem(data, size, budget);
    if (!problem.empty()) return badInput(where, problem);

    draco::DecoderBuffer buf;
    buf.Init(reinterpret_cast<const char*>(data), size);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buf);
    if (!decoded.ok()) return badInput(where, "Draco decoding failed: " + decoded.status().error_msg_string());
    const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
    if (!mesh) return badInput(where, "Draco decoding returned no mesh");

    const uint32_t points = mesh->num_points(), faces = mesh->num_faces();
    if (faces > budget.maxTriangles() || points > budget.maxElements())
        return badInput(where, "the decoded Draco mesh has " + str(faces) + " triangles and " + str(points) +
                                   " vertices, more than the limit");
    Status st;
    const draco::PointAttribute* pos = attribute(*mesh, positionId, 3, "POSITION", where, st);
    const draco::PointAttribute* uv =
        texcoordId >= 0 && st ? attribute(*mesh, texcoordId, 2, "TEXCOORD_0", where, st) : nullptr;
    const draco::PointAttribute* normal =
        normalId >= 0 && st ? attribute(*mesh, normalId, 3, "NORMAL", where, st) : nullptr;
    if (!st) return st;
    if (!(st = readPoints(*pos, points, 3, "POSITION", where, out.positions))) return st;
    out.uvs.clear();
    if (uv && !(st = readPoints(*uv, points, 2, "TEXCOORD_0", where, out.uvs))) return st;
    out.normals.clear();
    if (normal && !(st = readPoints(*normal, points, 3, "NORMAL", where, out.normals))) return st;

    out.triangles.resize(size_t(faces) * 3);
    for (uint32_t f = 0; f < faces; ++f) {
        const draco::Mesh::Face& face = mesh->face(draco::FaceIndex(f));
        for (int c = 0; c < 3; ++c) {
            if (face[c].value() >= points)
                return badInput(where,
                                "Draco face " + str(f) + " uses point " + str(face[c].value()) + " of " + str(points));
            out.triangles[size_t(f) * 3 + c] = face[c].value();
        }
    }
    return Status::ok();
}

}  // namespace lt::gltf
