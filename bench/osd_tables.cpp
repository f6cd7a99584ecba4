// bench/osd_tables.cpp -- OpenSubdiv's own table build for adaptive Loop
// (osd_tables.h).
#include "osd_tables.h"

#include "baker_refiner.h"  // lt::buildRefiner: the baker's own refiner (looptess_baker_internal)

#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/osd/types.h>

#include <chrono>
#include <memory>

namespace ltbench {
namespace {

using Clock = std::chrono::steady_clock;
namespace Far = OpenSubdiv::Far;

double since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

template <typename V>
size_t arrayBytes(const V& v) {
    return v.size() * sizeof(v[0]);
}

void measure(const Far::StencilTable& stencils, const Far::PatchTable& patches, uint64_t refined, OsdBytes* bytes,
             OsdCounts* counts) {
    if (bytes) {
        *bytes = OsdBytes{};
        bytes->stencilSizes = arrayBytes(stencils.GetSizes());
        bytes->stencilOffsets = arrayBytes(stencils.GetOffsets());
        bytes->stencilIndices = arrayBytes(stencils.GetControlIndices());
        bytes->stencilWeights = arrayBytes(stencils.GetWeights());
        bytes->patchArrays = size_t(patches.GetNumPatchArrays()) * sizeof(OpenSubdiv::Osd::PatchArray);
        bytes->patchVertices = arrayBytes(patches.GetPatchControlVerticesTable());
        bytes->patchParams = arrayBytes(patches.GetPatchParamTable());
        bytes->other = arrayBytes(patches.GetQuadOffsetsTable()) + arrayBytes(patches.GetSharpnessIndexTable()) +
                       arrayBytes(patches.GetSharpnessValues()) + arrayBytes(patches.GetVertexValenceTable());
        bytes->varyingVertices = size_t(patches.GetVaryingVertices().size()) * sizeof(Far::Index);
    }
    if (counts) {
        *counts = OsdCounts{};
        counts->refinedVertices = refined;
        counts->localPoints = uint64_t(patches.GetNumLocalPoints());
        counts->stencilWeights = stencils.GetWeights().size();
        counts->patchVertexCount = patches.GetPatchControlVerticesTable().size();
        for (int a = 0; a < patches.GetNumPatchArrays(); ++a) {
            const auto type = patches.GetPatchArrayDescriptor(a).GetType();
            (type == Far::PatchDescriptor::LOOP ? counts->regularPatches : counts->endCapPatches) +=
                uint64_t(patches.GetNumPatches(a));
        }
    }
}

}  // namespace

lt::Status buildOsdTables(const lt::InputMesh& mesh, int depth, OsdTimes& times, OsdBytes* bytes, OsdCounts* counts) {
    times = OsdTimes{};
    auto start = Clock::now();
    std::unique_ptr<Far::TopologyRefiner> refiner;
    lt::Status st = lt::buildRefiner(mesh, depth, "osd", refiner);
    if (!st) return st;
    times.refiner = since(start);

    start = Clock::now();
    Far::StencilTableFactory::Options so;
    so.interpolationMode = Far::StencilTableFactory::INTERPOLATE_VERTEX;
    so.generateOffsets = true;
    so.generateIntermediateLevels = true;
    so.factorizeIntermediateLevels = true;
    so.maxLevel = unsigned(depth);
    std::unique_ptr<const Far::StencilTable> vertexStencils(Far::StencilTableFactory::Create(*refiner, so));
    times.stencils = since(start);

    start = Clock::now();
    Far::PatchTableFactory::Options po{unsigned(depth)};
    po.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
    po.useInfSharpPatch = true;
    std::unique_ptr<const Far::PatchTable> patches(Far::PatchTableFactory::Create(*refiner, po));
    times.patches = since(start);
    if (!vertexStencils || !patches) return lt::Status::error(lt::Status::Internal, "OpenSubdiv built no tables");

    start = Clock::now();
    if (const Far::StencilTable* local = patches->GetLocalPointStencilTable()) {
        std::unique_ptr<const Far::StencilTable> all(
            Far::StencilTableFactory::AppendLocalPointStencilTable(*refiner, vertexStencils.get(), local));
        if (all) vertexStencils = std::move(all);
    }
    times.append = since(start);

    measure(*vertexStencils, *patches, uint64_t(refiner->GetNumVerticesTotal() - refiner->GetLevel(0).GetNumVertices()),
            bytes, counts);
    return lt::Status::ok();
}

}  // namespace ltbench
