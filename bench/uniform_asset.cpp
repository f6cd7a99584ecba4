// The global-refinement baseline as an lt::Asset (see uniform_asset.h).
#include "uniform_asset.h"

#include "baker_refiner.h"       // the baker's exact limit stencils (looptess_baker_internal)
#include "looptess/tools/osd.h"  // the mesh as Far topology, Sdc's masks

#include <algorithm>

namespace ltbench {
namespace {

using lt::OsdIndex;

constexpr uint32_t kPruned = UINT32_MAX;  // a vertex the asset leaves out (numberUniform)

// Which OpenSubdiv vertices of each level the asset keeps: keep[l][v]; an empty
// vector keeps every vertex of the level.
using KeepMasks = std::vector<std::vector<char>>;

// Global vertex index of every kept OpenSubdiv vertex of every level (kPruned for
// the others): level l's vertex points (by parent vertex), then its edge points (by
// parent edge). Level 0 (the control points) is always kept whole.
std::vector<std::vector<uint32_t>> numberUniform(const lt::Far::TopologyRefiner& refiner, int depth,
                                                 const KeepMasks& keep) {
    std::vector<std::vector<uint32_t>> global(size_t(depth) + 1);
    uint32_t next = uint32_t(refiner.GetLevel(0).GetNumVertices());
    global[0].resize(next);
    for (uint32_t v = 0; v < next; ++v) global[0][v] = v;
    for (int l = 1; l <= depth; ++l) {
        const auto& parent = refiner.GetLevel(l - 1);
        global[l].assign(size_t(refiner.GetLevel(l).GetNumVertices()), kPruned);
        auto number = [&](OsdIndex child) {
            if (keep[l].empty() || keep[l][child]) global[l][child] = next++;
        };
        for (OsdIndex p = 0; p < parent.GetNumVertices(); ++p) number(parent.GetVertexChildVertex(p));
        for (OsdIndex e = 0; e < parent.GetNumEdges(); ++e) number(parent.GetEdgeChildVertex(e));
    }
    return global;
}

// Level l's refinement: every kept vertex point and edge point (`childGlobal` not
// kPruned), with the baker's masks.
void fillRefinement(const lt::Far::TopologyRefiner& refiner, int l, const std::vector<uint32_t>& parentGlobal,
                    const std::vector<uint32_t>& childGlobal, uint32_t firstVertex, lt::Refinement& r) {
    const auto& parent = refiner.GetLevel(l - 1);
    r.firstVertex = firstVertex;
    r.vertexRingStart.push_back(0);
    r.maskStart.push_back(0);
    std::vector<double> weights;
    for (OsdIndex p = 0; p < parent.GetNumVertices(); ++p) {
        if (childGlobal[parent.GetVertexChildVertex(p)] == kPruned) continue;
        uint32_t local = r.vertexPointCount();
        r.vertexParent.push_back(parentGlobal[p]);
        for (OsdIndex e : parent.GetVertexEdges(p)) r.vertexRing.push_back(parentGlobal[lt::otherEnd(parent, e, p)]);
        r.vertexRingStart.push_back(uint32_t(r.vertexRing.size()));
        if (lt::vertexMask(refiner, l - 1, p, weights)) {
            r.maskedVertex.push_back(local);
            for (size_t j = 1; j < weights.size(); ++j) r.maskWeights.push_back(float(weights[j]));
            r.maskStart.push_back(uint32_t(r.maskWeights.size()));
        }
    }
    for (OsdIndex e = 0; e < parent.GetNumEdges(); ++e) {
        if (childGlobal[parent.GetEdgeChildVertex(e)] == kPruned) continue;
        uint32_t local = r.edgePointCount();
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
            r.creaseEdge.push_back(local);
            r.creaseWeight.push_back(w);
        }
    }
}

// Level `depth`'s limit stencils, one per drawn vertex (`drawn[v]`, or every
// vertex when `drawn` is empty) and sector, in global vertex order, each ring
// starting at its smallest global index (as lt::bake orders them).
// `first[k] .. first[k + 1]` are the stencils of the level's k-th kept vertex and
// `sector` names each stencil's sector.
void fillStencils(const lt::Far::TopologyRefiner& refiner, int depth, const std::vector<uint32_t>& g,
                  uint32_t firstVertex, const std::vector<char>& drawn, lt::LimitStencils& ls,
                  std::vector<uint32_t>& first, std::vector<OsdIndex>& sector) {
    const auto& level = refiner.GetLevel(depth);
    std::vector<OsdIndex> byGlobal;
    for (size_t v = 0; v < g.size(); ++v)
        if (g[v] != kPruned) {
            if (byGlobal.size() <= g[v] - firstVertex) byGlobal.resize(g[v] - firstVertex + 1);
            byGlobal[g[v] - firstVertex] = OsdIndex(v);
        }
    first.assign(1, 0);
    ls.start.assign(1, 0);
    lt::LimitStencil stencil;
    std::vector<std::pair<OsdIndex, OsdIndex>> sectors;  // (sector, a face of it)
    for (OsdIndex v : byGlobal) {
        sectors.clear();
        if (!drawn.empty() && !drawn[v]) {
            first.push_back(ls.count());
            continue;
        }
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

// Level `depth`: the stencils of the drawn faces' vertices, and every drawn face
// (base face in `drawnBase`, or every face when it is empty; holes never) as an IPP.
void fillFinest(const lt::Far::TopologyRefiner& refiner, int depth, const std::vector<uint32_t>& g,
                uint32_t firstVertex, const std::vector<uint32_t>& base, const std::vector<char>& drawnBase,
                lt::Level& out) {
    const auto& level = refiner.GetLevel(depth);
    auto isDrawn = [&](OsdIndex f) { return !level.IsFaceHole(f) && (drawnBase.empty() || drawnBase[base[f]]); };
    std::vector<char> drawnVertex;
    if (!drawnBase.empty()) {
        drawnVertex.assign(size_t(level.GetNumVertices()), 0);
        for (OsdIndex f = 0; f < level.GetNumFaces(); ++f)
            if (isDrawn(f))
                for (OsdIndex v : level.GetFaceVertices(f)) drawnVertex[v] = 1;
    }
    std::vector<uint32_t> first;
    std::vector<OsdIndex> sector;
    fillStencils(refiner, depth, g, firstVertex, drawnVertex, out.limit, first, sector);
    for (OsdIndex f = 0; f < level.GetNumFaces(); ++f) {
        if (!isDrawn(f)) continue;
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

// The vertices a chunk's frame reads (see buildUniformChunk), level by level from
// the finest: the drawn faces' vertices and their 1-rings (the limit stencils'
// rings), then on each coarser level the parents, rings and edge stencils
// (endpoints and opposite vertices) of the vertices kept below it.
KeepMasks closure(const lt::Far::TopologyRefiner& refiner, int depth, const std::vector<uint32_t>& base,
                  const std::vector<char>& drawnBase) {
    KeepMasks keep(size_t(depth) + 1);
    const auto& finest = refiner.GetLevel(depth);
    keep[depth].assign(size_t(finest.GetNumVertices()), 0);
    for (OsdIndex f = 0; f < finest.GetNumFaces(); ++f) {
        if (finest.IsFaceHole(f) || !drawnBase[base[f]]) continue;
        for (OsdIndex v : finest.GetFaceVertices(f)) {
            keep[depth][v] = 1;
            for (OsdIndex e : finest.GetVertexEdges(v)) keep[depth][lt::otherEnd(finest, e, v)] = 1;
        }
    }
    for (int l = depth; l >= 1; --l) {
        const auto& parent = refiner.GetLevel(l - 1);
        std::vector<char>& up = keep[l - 1];
        up.assign(size_t(parent.GetNumVertices()), 0);
        for (OsdIndex p = 0; p < parent.GetNumVertices(); ++p) {
            if (!keep[l][parent.GetVertexChildVertex(p)]) continue;
            up[p] = 1;
            for (OsdIndex e : parent.GetVertexEdges(p)) up[lt::otherEnd(parent, e, p)] = 1;
        }
        for (OsdIndex e = 0; e < parent.GetNumEdges(); ++e) {
            if (!keep[l][parent.GetEdgeChildVertex(e)]) continue;
            for (OsdIndex f : parent.GetEdgeFaces(e))
                for (OsdIndex v : parent.GetFaceVertices(f)) up[v] = 1;
            for (OsdIndex v : parent.GetEdgeVertices(e)) up[v] = 1;
        }
    }
    return keep;
}

}  // namespace

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

namespace {

// The uniform asset of `mesh` at `depth`, drawing the base faces in `drawnBase`
// (every face when empty) and keeping only the vertices they read.
lt::Status buildFrom(const lt::InputMesh& mesh, int depth, const std::vector<char>& drawnBase, lt::Asset& out) {
    if (depth < 1 || depth > 8)
        return lt::Status::error(lt::Status::Usage, "depth " + std::to_string(depth) + " is not in 1..8");
    std::unique_ptr<lt::Far::TopologyRefiner> refiner;
    lt::Status st = lt::createRefiner(mesh, "input", refiner);  // the baker's topology and options
    if (!st) return st;
    const auto& level0 = refiner->GetLevel(0);
    if (mesh.boundary == lt::BoundaryInterpolation::None)
        for (OsdIndex v = 0; v < level0.GetNumVertices(); ++v)
            if (level0.IsVertexBoundary(v))
                return lt::Status::error(lt::Status::Unsupported,
                                         "boundary interpolation none on a mesh with a boundary");
    lt::refineUniform(*refiner, depth);  // the last level's edges and rings: the limit stencils read them

    std::vector<uint32_t> base = baseFaces(*refiner, depth);
    KeepMasks keep = drawnBase.empty() ? KeepMasks(size_t(depth) + 1) : closure(*refiner, depth, base, drawnBase);
    std::vector<std::vector<uint32_t>> global = numberUniform(*refiner, depth, keep);
    out = lt::Asset{};
    out.positions = mesh.positions;
    out.faces = mesh.faces;
    out.boundary = mesh.boundary;
    out.creaseMethod = mesh.creaseMethod;
    out.levels.resize(size_t(depth) + 1);
    uint32_t firstVertex = mesh.vertexCount();
    for (int l = 1; l <= depth; ++l) {
        fillRefinement(*refiner, l, global[l - 1], global[l], firstVertex, out.levels[l].refinement);
        firstVertex += out.levels[l].refinement.vertexCount();
    }
    fillFinest(*refiner, depth, global[depth], out.levels[depth].refinement.firstVertex, base, drawnBase,
               out.levels[depth]);
    // A pruned vertex read by a kept one would show here as an index out of range.
    st = lt::validateAsset(out, "uniform asset");
    return st ? st : lt::Status::error(lt::Status::Internal, st.message);
}

// The faces of `chunk` and every face sharing a vertex with one of them, as a mesh
// of its own (vertices renumbered, creases, corners and holes kept where their
// edges, vertices and faces are); drawn[f] marks the chunk's own faces. The cut
// through the mesh becomes a boundary: boundary interpolation None (which only a
// closed mesh can use, buildFrom) becomes EdgeOnly, which changes nothing the
// chunk's faces read.
lt::Status subMesh(const lt::InputMesh& mesh, const std::vector<uint32_t>& chunk, lt::InputMesh& sub,
                   std::vector<char>& drawn) {
    if (!mesh.edits.empty())
        return lt::Status::error(lt::Status::Unsupported, "chunks of a mesh with hierarchical edits");
    const uint32_t nv = mesh.vertexCount(), nf = mesh.faceCount();
    std::vector<char> inChunk(nf, 0), touched(nv, 0);
    for (uint32_t f : chunk) {
        if (f >= nf) return lt::Status::error(lt::Status::Usage, "chunk face " + std::to_string(f) + " is not a face");
        inChunk[f] = 1;
        for (int c = 0; c < 3; ++c) touched[mesh.faces[3 * f + c]] = 1;
    }
    sub = lt::InputMesh{};
    sub.boundary =
        mesh.boundary == lt::BoundaryInterpolation::None ? lt::BoundaryInterpolation::EdgeOnly : mesh.boundary;
    sub.creaseMethod = mesh.creaseMethod;
    drawn.clear();
    std::vector<uint32_t> vertexMap(nv, kPruned), faceMap(nf, kPruned);
    for (uint32_t f = 0; f < nf; ++f) {
        const uint32_t* fv = &mesh.faces[3 * f];
        if (!touched[fv[0]] && !touched[fv[1]] && !touched[fv[2]]) continue;
        faceMap[f] = sub.faceCount();
        drawn.push_back(inChunk[f]);
        for (int c = 0; c < 3; ++c) {
            uint32_t& v = vertexMap[fv[c]];
            if (v == kPruned) {
                v = sub.vertexCount();
                sub.positions.insert(sub.positions.end(), &mesh.positions[3 * fv[c]], &mesh.positions[3 * fv[c] + 3]);
            }
            sub.faces.push_back(v);
        }
        if (!mesh.faceUVs.empty())
            sub.faceUVs.insert(sub.faceUVs.end(), &mesh.faceUVs[6 * f], &mesh.faceUVs[6 * f + 6]);
    }
    std::vector<std::pair<uint32_t, uint32_t>> edges;  // the submesh's edges, (min, max)
    for (size_t i = 0; i < sub.faces.size(); i += 3)
        for (int c = 0; c < 3; ++c) {
            uint32_t a = sub.faces[i + c], b = sub.faces[i + (c + 1) % 3];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    std::sort(edges.begin(), edges.end());
    for (const auto& c : mesh.creases) {
        uint32_t a = vertexMap[c.a], b = vertexMap[c.b];
        if (a != kPruned && b != kPruned &&
            std::binary_search(edges.begin(), edges.end(), std::make_pair(std::min(a, b), std::max(a, b))))
            sub.creases.push_back({a, b, c.sharpness});
    }
    for (const auto& c : mesh.corners)
        if (vertexMap[c.vertex] != kPruned) sub.corners.push_back({vertexMap[c.vertex], c.sharpness});
    for (uint32_t h : mesh.holes)
        if (h < nf && faceMap[h] != kPruned) sub.holes.push_back(faceMap[h]);
    return lt::Status::ok();
}

// Recursive coordinate bisection of `faces[begin, end)` (by centroid, across the
// longest extent) into `parts` chunks of nearly equal size.
void bisect(const lt::InputMesh& mesh, std::vector<uint32_t>& faces, size_t begin, size_t end, uint32_t parts,
            std::vector<std::vector<uint32_t>>& out) {
    if (parts <= 1 || end - begin <= 1) {
        out.emplace_back(faces.begin() + begin, faces.begin() + end);
        std::sort(out.back().begin(), out.back().end());
        return;
    }
    auto centroid = [&](uint32_t f, int axis) {
        const uint32_t* fv = &mesh.faces[3 * f];
        return mesh.positions[3 * fv[0] + axis] + mesh.positions[3 * fv[1] + axis] + mesh.positions[3 * fv[2] + axis];
    };
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (size_t i = begin; i < end; ++i)
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], centroid(faces[i], a));
            hi[a] = std::max(hi[a], centroid(faces[i], a));
        }
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
    uint32_t left = parts / 2;
    size_t mid = begin + (end - begin) * left / parts;
    std::nth_element(faces.begin() + begin, faces.begin() + mid, faces.begin() + end,
                     [&](uint32_t a, uint32_t b) { return centroid(a, axis) < centroid(b, axis); });
    bisect(mesh, faces, begin, mid, left, out);
    bisect(mesh, faces, mid, end, parts - left, out);
}

}  // namespace

lt::Status buildUniformAsset(const lt::InputMesh& mesh, int depth, lt::Asset& out) {
    return buildFrom(mesh, depth, {}, out);
}

lt::Status buildUniformChunk(const lt::InputMesh& mesh, int depth, const std::vector<uint32_t>& chunk, lt::Asset& out) {
    lt::InputMesh sub;
    std::vector<char> drawn;
    lt::Status st = subMesh(mesh, chunk, sub, drawn);
    return st ? buildFrom(sub, depth, drawn, out) : st;
}

std::vector<std::vector<uint32_t>> partitionFaces(const lt::InputMesh& mesh, uint32_t parts) {
    std::vector<uint32_t> faces(mesh.faceCount());
    for (uint32_t f = 0; f < faces.size(); ++f) faces[f] = f;
    std::vector<std::vector<uint32_t>> out;
    bisect(mesh, faces, 0, faces.size(), std::max(1u, parts), out);
    return out;
}

}  // namespace ltbench
