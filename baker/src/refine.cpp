// The baker's refiners (refine.h, baker_refiner.h): the bridge's mapping of the mesh
// (looptess/tools/osd.h) with the slit isolation channel added.
#include "refine.h"

#include <cassert>

namespace lt {
namespace {

// A mesh or level for Far, with channel kIsolationChannel: a value per face corner,
// or none.
struct Descriptor {
    FarTopology topology;
    std::vector<int> isolation;
    int isolationValues = 0;

    std::unique_ptr<Far::TopologyRefiner> create(Sdc::Options sdc) const {
        Far::TopologyDescriptor desc = topology.descriptor();
        Far::TopologyDescriptor::FVarChannel channel;
        if (!isolation.empty()) {
            channel.numValues = isolationValues;
            channel.valueIndices = isolation.data();
            desc.numFVarChannels = 1;
            desc.fvarChannels = &channel;
            // Linear channels are never isolated (Far::TopologyRefiner::RefineAdaptive).
            sdc.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_NONE);
        }
        return createRefiner(desc, sdc);
    }
};

// `mesh` with `slits` marked in the isolation channel: each slit's middle face takes
// a value of its own at the vertex; every other corner takes its vertex's index.
Descriptor isolated(const InputMesh& mesh, const std::vector<SlitCorner>& slits) {
    Descriptor d{meshTopology(mesh), {}, 0};
    const std::vector<int>& faceVerts = d.topology.faceVerts;
    d.isolation = faceVerts;
    d.isolationValues = d.topology.vertexCount;
    for (const SlitCorner& s : slits)
        for (size_t c = size_t(s.face) * 3; c < size_t(s.face) * 3 + 3; ++c)
            if (faceVerts[c] == s.vertex) d.isolation[c] = d.isolationValues++;
    return d;
}

// Level `level` as a mesh of its own (levelTopology), its isolation channel as
// refined: the vertex points of slits.
Descriptor levelDescriptor(const Far::TopologyLevel& level) {
    Descriptor d{levelTopology(level), {}, 0};
    if (level.GetNumFVarChannels() > kIsolationChannel) {
        d.isolationValues = level.GetNumFVarValues(kIsolationChannel);
        for (OsdIndex f = 0; f < level.GetNumFaces(); ++f)
            for (OsdIndex x : level.GetFaceFVarValues(f, kIsolationChannel)) d.isolation.push_back(x);
    }
    return d;
}

}  // namespace

Status buildRefiner(const InputMesh& mesh, int maxDepth, const std::string& name,
                    std::unique_ptr<Far::TopologyRefiner>& refiner, const RefineHook& beforeRefine) {
    OsdErrors errors;
    const Sdc::Options sdc = sdcOptions(mesh.boundary, mesh.creaseMethod);
    refiner = createRefiner(meshTopology(mesh).descriptor(), sdc);
    Status hook;
    if (refiner && errors.empty() && beforeRefine) hook = beforeRefine(*refiner, maxDepth);
    if (refiner && errors.empty() && hook) {
        // Slits on regular runs are isolated: the channel that marks them goes in at
        // creation, so the refiner is made again.
        const std::vector<SlitCorner> slits = slitVertices(*refiner, mesh.positions);
        if (!slits.empty()) refiner = isolated(mesh, slits).create(sdc);
    }
    if (refiner && hook) refineAdaptive(*refiner, maxDepth);
    if (!hook) {
        refiner.reset();
        return hook;
    }
    if (!refiner || !errors.empty()) {
        refiner.reset();
        return errors.rejected(name);
    }
    return Status::ok();
}

Status buildTopology(const InputMesh& mesh, int maxDepth, int uniformDepth, const std::string& name, Topology& topology,
                     const RefineHook& beforeRefine) {
    assert(uniformDepth >= 0 && uniformDepth <= maxDepth);
    topology = Topology{};
    if (uniformDepth == 0) return buildRefiner(mesh, maxDepth, name, topology.adaptive, beforeRefine);
    OsdErrors errors;
    const Sdc::Options sdc = sdcOptions(mesh.boundary, mesh.creaseMethod);
    std::unique_ptr<Far::TopologyRefiner> uniform = createRefiner(meshTopology(mesh).descriptor(), sdc);
    if (!uniform || !errors.empty()) return errors.rejected(name);
    if (beforeRefine)
        if (Status hook = beforeRefine(*uniform, maxDepth); !hook) return hook;
    // As buildRefiner; the channel refines with the levels, and level K's goes on.
    if (const std::vector<SlitCorner> slits = slitVertices(*uniform, mesh.positions); !slits.empty())
        uniform = isolated(mesh, slits).create(sdc);
    assert(maxDepth >= uniformDepth);
    refineUniform(*uniform, uniformDepth);  // the last level's edges carry its sharpness
    std::unique_ptr<Far::TopologyRefiner> adaptive = levelDescriptor(uniform->GetLevel(uniformDepth)).create(sdc);
    if (adaptive && maxDepth > uniformDepth) refineAdaptive(*adaptive, maxDepth - uniformDepth);
    if (!adaptive || !errors.empty()) return errors.rejected(name);
    topology.uniform = std::move(uniform);
    topology.adaptive = std::move(adaptive);
    topology.uniformDepth = uniformDepth;
    return Status::ok();
}

}  // namespace lt
