// The global-refinement baseline as an lt::Asset (see uniform_asset.h).
#include "uniform_asset.h"

#include "refine.h"  // baker/src: buildRefiner, Sdc masks, exact limit stencils

#include <algorithm>

namespace ltbench {
namespace {

using lt::OsdIndex;

// Global vertex index of every OpenSubdiv vertex of every level: level l's vertex
// points (by parent vertex), then its edge points (by parent edge).
std::vector<std::vector<uint32_t>> numberUniform(const lt::Far::TopologyRefiner& refiner, int depth) {
    std::vector<std::vector<uint32_t>> global(size_t(depth) + 1);
    uint32_t next = uint32_t(refiner.GetLevel(0).GetNumVertices());
    global[0].resize(next);
    for (uint32_t v = 0; v < next; ++v) global[0][v] = v;
    for (int l = 1; l <= depth; ++l) {
        const auto& parent = refiner.GetLevel(l - 1);
        global[l].assign(size_t(refiner.GetLevel(l).GetNumVertices()), 0);
        for (OsdIndex p = 0; p < parent.GetNumVertices(); ++p) global[l][parent.GetVertexChildVertex(p)] = next++;
        for (OsdIndex e = 0; e < parent.GetNumEdges(); ++e) global[l][parent.GetEdgeChildVertex(e)] = next++;
    }
    return global;
}

// Level l's refinement: every parent vertex and edge, with the baker's masks.
void fillRefinement(const lt::Far::TopologyRefiner& refiner, int l, const std::vector<uint32_t>& parentGlobal,
                    uint32_t firstVertex, lt::Refinement& r) {
    const auto& parent = refiner.GetLevel(l - 1);
    r.firstVertex = firstVertex;
    r.vertexRingStart.push_back(0);
    r.maskStart.push_back(0);
    std::vector<double> weights;
    for (OsdIndex p = 0; p < parent.GetNumVertices(); ++p) {
        r.vertexParent.push_back(parentGlobal[p]);
        for (OsdIndex e : parent.GetVertexEdges(p)) r.vertexRing.push_back(parentGlobal[lt::otherEnd(parent, e, p)]);
        r.vertexRingStart.push_back(uint32_t(r.vertexRing.size()));
        if (lt::vertexMask(refiner, l - 1, p, weights)) {
            r.maskedVertex.push_back(uint32_t(p));
            for (size_t j = 1; j < weights.size(); ++j) r.maskWeights.push_back(float(weights[j]));
            r.maskStart.push_back(uint32_t(r.maskWeights.size()));
        }
    }
    for (OsdIndex e = 0; e < parent.GetNumEdges(); ++e) {
        auto ev = parent.GetEdgeVertices(e);
        uint32_t a = parentGlobal[ev[0]], b = parentGlobal[ev[1]], opp[2] = {a, a};
        float w = lt::edgeCreaseWeight(refiner, l - 1, e);
        auto faces = parent.GetEdgeFaces(e);
        for (int k = 0; k < faces.size() && k < 2 && w < 1.0f; ++k)
            for (OsdIndex v : parent.GetFaceVertices(faces[k]))
                if (v != ev[0] && v != ev[1]) opp[k] = parentGlobal[v];
        if (faces.size() == 1) opp[1] = opp[0];  // boundary: d == c
        for (uint32_t x : {a, b, opp[0], opp[1]}) r.edgeVerts.push_back(x);
        if (w > 0.0f) {
            r.creaseEdge.push_back(uint32_t(e));
            r.creaseWeight.push_back(w);
        }
    }
}

// Level `depth`'s limit stencils, one per vertex and sector, in global vertex
// order, each ring starting at its smallest global index (as lt::bake orders them).
// `first[k] .. first[k + 1]` are the stencils of the level's k-th vertex and
// `sector` names each stencil's sector.
void fillStencils(const lt::Far::TopologyRefiner& refiner, int depth, const std::vector<uint32_t>& g,
                  uint32_t firstVertex, lt::LimitStencils& ls, std::vector<uint32_t>& first, std::vector<OsdIndex>& sector) {
    const auto& level = refiner.GetLevel(depth);
    std::vector<OsdIndex> byGlobal(g.size());
    for (size_t v = 0; v < g.size(); ++v) byGlobal[g[v] - firstVertex] = OsdIndex(v);
    first.assign(1, 0);
    ls.start.assign(1, 0);
    lt::LimitStencil stencil;
    std::vector<std::pair<OsdIndex, OsdIndex>> sectors;  // (sector, a face of it)
    for (OsdIndex v : byGlobal) {
        sectors.clear();
        for (OsdIndex f : level.GetVertexFaces(v)) sectors.emplace_back(lt::limitSector(refiner, depth, v, f), f);
        std::sort(sectors.begin(), sectors.end());
        for (size_t k = 0; k < sectors.size(); ++k) {
            if (k > 0 && sectors[k].first == sectors[k - 1].first) continue;
            lt::limitStencil(refiner, depth, v, sectors[k].second, stencil);
            size_t n = stencil.points.size() - 1, start = 0;
            for (size_t j = 1; j < n; ++j)
                if (g[stencil.points[1 + j]] < g[stencil.points[1 + start]]) start = j;
            if (!stencil.smooth) {
                if (ls.masked.empty()) ls.maskStart.push_back(0);
                ls.masked.push_back(ls.count());
            }
            ls.vertex.push_back(g[v]);
            for (size_t j = 0; j < n; ++j) {
                size_t w = 1 + (start + j) % n;
                ls.ring.push_back(g[stencil.points[w]]);
                if (stencil.smooth) continue;
                ls.position.push_back(float(stencil.position[w]));
                ls.tangentU.push_back(float(stencil.tangentU[w]));
                ls.tangentV.push_back(float(stencil.tangentV[w]));
            }
            ls.start.push_back(uint32_t(ls.ring.size()));
            if (!stencil.smooth) ls.maskStart.push_back(uint32_t(ls.position.size()));
            sector.push_back(sectors[k].first);
        }
        first.push_back(ls.count());
    }
}

// Base face of every face of every level, from the parent links.
std::vector<uint32_t> baseFaces(const lt::Far::TopologyRefiner& refiner, int depth) {
    std::vector<uint32_t> base(size_t(refiner.GetLevel(0).GetNumFaces()));
    for (size_t f = 0; f < base.size(); ++f) base[f] = uint32_t(f);
    for (int l = 1; l <= depth; ++l) {
        const auto& level = refiner.GetLevel(l);
        std::vector<uint32_t> child(size_t(level.GetNumFaces()));
        for (OsdIndex f = 0; f < level.GetNumFaces(); ++f) child[f] = base[level.GetFaceParentFace(f)];
        base.swap(child);
    }
    return base;
}

// Level `depth`: its stencils, and every face that is not a hole as an IPP.
void fillFinest(const lt::Far::TopologyRefiner& refiner, int depth, const std::vector<uint32_t>& g, uint32_t firstVertex,
                lt::Level& out) {
    const auto& level = refiner.GetLevel(depth);
    std::vector<uint32_t> first;
    std::vector<OsdIndex> sector;
    fillStencils(refiner, depth, g, firstVertex, out.limit, first, sector);
    std::vector<uint32_t> base = baseFaces(refiner, depth);
    for (OsdIndex f = 0; f < level.GetNumFaces(); ++f) {
        if (level.IsFaceHole(f)) continue;
        lt::IrregularFace face;
        auto fv = level.GetFaceVertices(f);
        for (int c = 0; c < 3; ++c) {
            uint32_t k = g[fv[c]] - firstVertex, s = first[k];
            if (first[k + 1] - s > 1) {
                OsdIndex want = lt::limitSector(refiner, depth, fv[c], f);
                while (sector[s] != want) ++s;
            }
            face.corners[c] = s;
        }
        face.param.baseFace = base[f];
        face.param.level = uint8_t(depth);
        out.irregular.push_back(face);
    }
}

} // namespace

UniformCounts uniformCounts(const lt::Asset& uniform) {
    UniformCounts c;
    c.faces = uniform.levels.back().irregular.size();
    c.vertices = uniform.totalVertexCount();
    for (const lt::Level& level : uniform.levels) {
        const lt::Refinement& r = level.refinement;
        // gpu_layout.h: parents, ring starts and per-point mask offsets; rings; mask
        // weights; 4 vertices and a weight offset per edge point; crease pairs.
        c.refinementWords += 3 * uint64_t(r.vertexPointCount()) + 1 + r.vertexRing.size() + r.maskWeights.size() +
                             5 * uint64_t(r.edgePointCount()) + 2 * r.creaseEdge.size();
    }
    return c;
}

uint64_t leanBytes(const UniformCounts& c) { return 12 * c.vertices + 4 * c.refinementWords + 12 * c.faces; }

lt::Status buildUniformAsset(const lt::InputMesh& mesh, int depth, lt::Asset& out) {
    if (depth < 1 || depth > 8) return lt::Status::error(lt::Status::Usage, "depth " + std::to_string(depth) + " is not in 1..8");
    std::unique_ptr<lt::Far::TopologyRefiner> refiner;
    lt::Status st = lt::buildRefiner(mesh, 1, "input", refiner);  // the baker's topology and options
    if (!st) return st;
    const auto& base = refiner->GetLevel(0);
    if (mesh.boundary == lt::BoundaryInterpolation::None)
        for (OsdIndex v = 0; v < base.GetNumVertices(); ++v)
            if (base.IsVertexBoundary(v))
                return lt::Status::error(lt::Status::Unsupported, "boundary interpolation none on a mesh with a boundary");
    refiner->Unrefine();
    lt::Far::TopologyRefiner::UniformOptions uniform(depth);
    uniform.fullTopologyInLastLevel = true;  // the limit stencils need its edges and rings
    refiner->RefineUniform(uniform);

    std::vector<std::vector<uint32_t>> global = numberUniform(*refiner, depth);
    out = lt::Asset{};
    out.positions = mesh.positions;
    out.faces = mesh.faces;
    out.boundary = mesh.boundary;
    out.creaseMethod = mesh.creaseMethod;
    out.levels.resize(size_t(depth) + 1);
    uint32_t firstVertex = mesh.vertexCount();
    for (int l = 1; l <= depth; ++l) {
        fillRefinement(*refiner, l, global[l - 1], firstVertex, out.levels[l].refinement);
        firstVertex += out.levels[l].refinement.vertexCount();
    }
    fillFinest(*refiner, depth, global[depth], out.levels[depth].refinement.firstVertex, out.levels[depth]);
    st = lt::validateAsset(out, "uniform asset");
    return st ? st : lt::Status::error(lt::Status::Internal, st.message);
}

} // namespace ltbench
