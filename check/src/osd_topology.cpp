// The oracle's own mapping of a mesh to Far (osd_topology.h).
#include "osd_topology.h"

#include "looptess/tools/osd.h"  // OsdErrors: OpenSubdiv's messages, nothing of the mapping

#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

namespace lt {

OracleMesh oracleMesh(const InputMesh& mesh) {
    OracleMesh m;
    m.vertices = int(mesh.vertexCount());
    m.triangles.assign(mesh.faces.begin(), mesh.faces.end());
    for (const InputMesh::Crease& c : mesh.creases) m.sharp[edgeKey(int(c.a), int(c.b))] = c.sharpness;
    for (const InputMesh::Corner& c : mesh.corners) m.corners[int(c.vertex)] = c.sharpness;
    m.holes.assign(mesh.holes.begin(), mesh.holes.end());
    return m;
}

Sdc::Options oracleOptions(const InputMesh& mesh) {
    Sdc::Options options;
    options.SetVtxBoundaryInterpolation(
        mesh.boundary == BoundaryInterpolation::EdgeOnly        ? Sdc::Options::VTX_BOUNDARY_EDGE_ONLY
        : mesh.boundary == BoundaryInterpolation::EdgeAndCorner ? Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER
                                                                : Sdc::Options::VTX_BOUNDARY_NONE);
    options.SetCreasingMethod(mesh.creaseMethod == CreaseMethod::Chaikin ? Sdc::Options::CREASE_CHAIKIN
                                                                         : Sdc::Options::CREASE_UNIFORM);
    return options;
}

std::unique_ptr<Far::TopologyRefiner> oracleRefiner(const OracleMesh& m, const Sdc::Options& options) {
    std::vector<int> counts(m.triangles.size() / 3, 3), pairs, cornerVerts;
    std::vector<float> weights, cornerWeights;
    for (const auto& [e, s] : m.sharp) {
        pairs.push_back(e.first);
        pairs.push_back(e.second);
        weights.push_back(s);
    }
    for (const auto& [v, s] : m.corners) {
        cornerVerts.push_back(v);
        cornerWeights.push_back(s);
    }
    Far::TopologyDescriptor d;
    d.numVertices = m.vertices;
    d.numFaces = int(counts.size());
    d.numVertsPerFace = counts.data();
    d.vertIndicesPerFace = m.triangles.data();
    d.numCreases = int(weights.size());
    d.creaseVertexIndexPairs = pairs.data();
    d.creaseWeights = weights.data();
    d.numCorners = int(cornerVerts.size());
    d.cornerVertexIndices = cornerVerts.data();
    d.cornerWeights = cornerWeights.data();
    d.numHoles = int(m.holes.size());
    d.holeIndices = m.holes.data();
    std::vector<int> values;  // channel 0, a value per face corner
    Far::TopologyDescriptor::FVarChannel channel;
    Sdc::Options sdc = options;
    if (!m.isolate.empty()) {
        std::vector<char> own(size_t(m.vertices), 0);
        for (int v : m.isolate) own[size_t(v)] = 1;
        channel.numValues = m.vertices;
        for (int v : m.triangles) values.push_back(own[size_t(v)] ? channel.numValues++ : v);
        channel.valueIndices = values.data();
        d.numFVarChannels = 1;
        d.fvarChannels = &channel;
        sdc.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_NONE);  // Far isolates no linear channel
    }
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    return std::unique_ptr<Far::TopologyRefiner>(Factory::Create(d, Factory::Options(Sdc::SCHEME_LOOP, sdc)));
}

Status oracleRefiner(const InputMesh& mesh, const std::string& name, std::unique_ptr<Far::TopologyRefiner>& out) {
    OsdErrors errors;
    out = oracleRefiner(oracleMesh(mesh), oracleOptions(mesh));
    if (out && errors.empty()) return Status::ok();
    out.reset();
    return errors.rejected(name);
}

}  // namespace lt
