// The OpenSubdiv bridge (looptess/tools/osd.h).
#include "looptess/tools/osd.h"

#include <opensubdiv/far/error.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#include <opensubdiv/sdc/crease.h>
#include <opensubdiv/sdc/loopScheme.h>

#include <algorithm>
#include <cassert>
#include <mutex>

namespace lt {
namespace {

// The innermost OsdErrors of this thread (its text), or null.
thread_local std::string* tlsOsdErrors = nullptr;

void osdErrorCallback(Far::ErrorType, const char* message) {
    if (tlsOsdErrors) {
        if (!tlsOsdErrors->empty()) *tlsOsdErrors += "; ";
        *tlsOsdErrors += message;
    }
}

void osdWarningCallback(const char*) {}

// Sdc's <typename EDGE> over a TopologyLevel.
class EdgeHood {
public:
    EdgeHood(const Far::TopologyLevel& level, OsdIndex edge) : level_(level), edge_(edge) {}
    int GetNumFaces() const { return level_.GetEdgeFaces(edge_).size(); }
    float GetSharpness() const { return level_.GetEdgeSharpness(edge_); }
    void GetChildSharpnesses(Sdc::Crease const&, float s[2]) const { s[0] = s[1] = GetSharpness() - 1.0f; }
    void GetNumVerticesPerFace(int counts[]) const {
        for (int i = 0; i < GetNumFaces(); ++i) counts[i] = 3;
    }

private:
    const Far::TopologyLevel& level_;
    OsdIndex edge_;
};

// Sdc's <typename VERTEX> over a parent TopologyLevel (and the child level when the
// vertex has a child).
class VertexHood {
public:
    VertexHood(const Far::TopologyLevel& parent, const Far::TopologyLevel* child, OsdIndex vertex, OsdIndex childVertex)
        : parent_(parent), child_(child), vertex_(vertex), childVertex_(childVertex) {}
    int GetNumEdges() const { return parent_.GetVertexEdges(vertex_).size(); }
    int GetNumFaces() const { return parent_.GetVertexFaces(vertex_).size(); }
    float GetSharpness() const { return parent_.GetVertexSharpness(vertex_); }
    float* GetSharpnessPerEdge(float s[]) const {
        auto edges = parent_.GetVertexEdges(vertex_);
        for (int i = 0; i < edges.size(); ++i) s[i] = parent_.GetEdgeSharpness(edges[i]);
        return s;
    }
    float GetChildSharpness(Sdc::Crease const&) const {
        assert(child_);
        return child_->GetVertexSharpness(childVertex_);
    }
    float* GetChildSharpnessPerEdge(Sdc::Crease const& crease, float s[]) const {
        std::vector<float> parentSharpness(GetNumEdges());
        GetSharpnessPerEdge(parentSharpness.data());
        crease.SubdivideEdgeSharpnessesAroundVertex(GetNumEdges(), parentSharpness.data(), s);
        return s;
    }

private:
    const Far::TopologyLevel& parent_;
    const Far::TopologyLevel* child_;
    OsdIndex vertex_, childVertex_;
};

using LoopScheme = Sdc::Scheme<Sdc::SCHEME_LOOP>;

}  // namespace

Sdc::Options sdcOptions(BoundaryInterpolation boundary, CreaseMethod creaseMethod) {
    Sdc::Options options;
    switch (boundary) {
    case BoundaryInterpolation::None: options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_NONE); break;
    case BoundaryInterpolation::EdgeAndCorner:
        options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
        break;
    case BoundaryInterpolation::EdgeOnly:
        options.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
        break;
    }
    options.SetCreasingMethod(creaseMethod == CreaseMethod::Chaikin ? Sdc::Options::CREASE_CHAIKIN
                                                                    : Sdc::Options::CREASE_UNIFORM);
    return options;
}

Far::TopologyDescriptor FarTopology::descriptor() const {
    Far::TopologyDescriptor desc;
    desc.numVertices = vertexCount;
    desc.numFaces = int(vertsPerFace.size());
    desc.numVertsPerFace = vertsPerFace.data();
    desc.vertIndicesPerFace = faceVerts.data();
    desc.numCreases = int(creaseWeights.size());
    desc.creaseVertexIndexPairs = creasePairs.data();
    desc.creaseWeights = creaseWeights.data();
    desc.numCorners = int(cornerWeights.size());
    desc.cornerVertexIndices = cornerVerts.data();
    desc.cornerWeights = cornerWeights.data();
    desc.numHoles = int(holes.size());
    desc.holeIndices = holes.data();
    return desc;
}

FarTopology meshTopology(const InputMesh& mesh) {
    FarTopology t;
    t.vertexCount = int(mesh.vertexCount());
    t.vertsPerFace.assign(mesh.faceCount(), 3);
    t.faceVerts.assign(mesh.faces.begin(), mesh.faces.end());
    for (const auto& c : mesh.creases) {
        t.creasePairs.push_back(int(c.a));
        t.creasePairs.push_back(int(c.b));
        t.creaseWeights.push_back(c.sharpness);
    }
    for (const auto& c : mesh.corners) {
        t.cornerVerts.push_back(int(c.vertex));
        t.cornerWeights.push_back(c.sharpness);
    }
    t.holes.assign(mesh.holes.begin(), mesh.holes.end());
    return t;
}

FarTopology levelTopology(const Far::TopologyLevel& level) {
    FarTopology t;
    t.vertexCount = level.GetNumVertices();
    for (OsdIndex f = 0; f < level.GetNumFaces(); ++f) {
        auto fv = level.GetFaceVertices(f);
        t.vertsPerFace.push_back(fv.size());
        t.faceVerts.insert(t.faceVerts.end(), fv.begin(), fv.end());
        if (level.IsFaceHole(f)) t.holes.push_back(f);
    }
    for (OsdIndex e = 0; e < level.GetNumEdges(); ++e) {
        float s = level.GetEdgeSharpness(e);
        if (!(s > 0.0f)) continue;
        auto ev = level.GetEdgeVertices(e);
        t.creasePairs.push_back(ev[0]);
        t.creasePairs.push_back(ev[1]);
        t.creaseWeights.push_back(s);
    }
    for (OsdIndex v = 0; v < level.GetNumVertices(); ++v) {
        float s = level.GetVertexSharpness(v);
        if (!(s > 0.0f)) continue;
        t.cornerVerts.push_back(v);
        t.cornerWeights.push_back(s);
    }
    return t;
}

// OpenSubdiv's callbacks are global: installed once (nothing else in looptess sets
// them), they hand each message to the thread's innermost scope.
OsdErrors::OsdErrors() : outer_(tlsOsdErrors) {
    static std::once_flag installed;
    std::call_once(installed, [] {
        Far::SetErrorCallback(osdErrorCallback);
        Far::SetWarningCallback(osdWarningCallback);
    });
    tlsOsdErrors = &text_;
}

OsdErrors::~OsdErrors() { tlsOsdErrors = outer_; }

Status OsdErrors::rejected(const std::string& name) const {
    return Status::error(Status::BadInput,
                         name + ": OpenSubdiv rejects the topology: " + (text_.empty() ? "unknown error" : text_));
}

std::unique_ptr<Far::TopologyRefiner> createRefiner(const Far::TopologyDescriptor& desc, const Sdc::Options& options) {
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    return std::unique_ptr<Far::TopologyRefiner>(Factory::Create(desc, Factory::Options(Sdc::SCHEME_LOOP, options)));
}

Status createRefiner(const InputMesh& mesh, const std::string& name, std::unique_ptr<Far::TopologyRefiner>& out) {
    OsdErrors errors;
    out = createRefiner(meshTopology(mesh).descriptor(), sdcOptions(mesh.boundary, mesh.creaseMethod));
    if (out && errors.empty()) return Status::ok();
    out.reset();
    return errors.rejected(name);
}

void refineAdaptive(Far::TopologyRefiner& refiner, int depth) {
    Far::TopologyRefiner::AdaptiveOptions adaptive(depth);
    adaptive.useInfSharpPatch = false;
    adaptive.considerFVarChannels = refiner.GetNumFVarChannels() > 0;
    refiner.RefineAdaptive(adaptive);
}

void refineUniform(Far::TopologyRefiner& refiner, int depth) {
    Far::TopologyRefiner::UniformOptions uniform(depth);
    uniform.fullTopologyInLastLevel = true;
    refiner.RefineUniform(uniform);
}

float edgeCreaseWeight(const Far::TopologyRefiner& refiner, int level, OsdIndex edge) {
    const Far::TopologyLevel& parent = refiner.GetLevel(level);
    const Far::TopologyLevel& child = refiner.GetLevel(level + 1);
    OsdIndex cv = parent.GetEdgeChildVertex(edge);
    assert(cv >= 0);
    // A smooth edge (the usual one): Sdc's smooth mask, vertex weights 3/8, so 0.
    if (parent.GetEdgeSharpness(edge) <= 0.0f && parent.GetEdgeFaces(edge).size() > 0) return 0.0f;
    EdgeHood hood(parent, edge);
    double vw[2] = {};
    // One face weight per face (more than two only at a non-manifold edge).
    const size_t faces = size_t(parent.GetEdgeFaces(edge).size()) + 1;
    double few[8] = {};
    std::vector<double> many(faces > 8 ? faces : 0, 0.0);
    SdcMask mask(vw, vw, faces > 8 ? many.data() : few);
    Sdc::Crease::Rule pRule =
        parent.GetEdgeSharpness(edge) > 0.0f ? Sdc::Crease::RULE_CREASE : Sdc::Crease::RULE_SMOOTH;
    LoopScheme(refiner.GetSchemeOptions()).ComputeEdgeVertexMask(hood, mask, pRule, child.GetVertexRule(cv));
    // Loop's edge masks are (1-w) (3/8, 3/8; 1/8, 1/8) + w (1/2, 1/2; 0, 0).
    double w = (vw[0] - 0.375) * 8.0;
    if (mask.GetNumFaceWeights() == 0) w = 1.0;
    return float(std::min(1.0, std::max(0.0, w)));
}

bool vertexMask(const Far::TopologyRefiner& refiner, int level, OsdIndex vertex, std::vector<double>& weights) {
    const Far::TopologyLevel& parent = refiner.GetLevel(level);
    const Far::TopologyLevel& child = refiner.GetLevel(level + 1);
    OsdIndex cv = parent.GetVertexChildVertex(vertex);
    assert(cv >= 0);
    Sdc::Crease::Rule pRule = parent.GetVertexRule(vertex);
    Sdc::Crease::Rule cRule = child.GetVertexRule(cv);
    auto smoothLike = [](Sdc::Crease::Rule r) { return r == Sdc::Crease::RULE_SMOOTH || r == Sdc::Crease::RULE_DART; };
    if (smoothLike(pRule) && smoothLike(cRule)) return false;

    int n = parent.GetVertexEdges(vertex).size();
    weights.assign(size_t(n) + 1, 0.0);
    std::vector<double> faceWeights(size_t(parent.GetVertexFaces(vertex).size()) + 1, 0.0);
    SdcMask mask(&weights[0], &weights[1], faceWeights.data());
    VertexHood hood(parent, &child, vertex, cv);
    LoopScheme(refiner.GetSchemeOptions()).ComputeVertexVertexMask(hood, mask, pRule, cRule);
    assert(mask.GetNumFaceWeights() == 0);
    if (mask.GetNumEdgeWeights() == 0) std::fill(weights.begin() + 1, weights.end(), 0.0);
    return true;
}

}  // namespace lt
