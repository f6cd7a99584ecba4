// EditRegion (edit_region.h).
#include "edit_region.h"

#include <algorithm>
#include <map>
#include <numeric>

namespace lt {

std::string editName(const InputMesh::VertexEdit& edit) {
    std::string s = "face " + std::to_string(edit.face) + " path";
    for (uint8_t c : edit.path) s += " " + std::to_string(int(c));
    return s + " vertex " + std::to_string(int(edit.vertex));
}

namespace {

// parent[f] of every face f of level l (1 <= l <= K: uniform levels are complete).
std::vector<OsdIndex> parentFaces(const Topology& topology, int l) {
    const Far::TopologyLevel& parent = topology.level(l - 1);
    std::vector<OsdIndex> out(size_t(topology.level(l).GetNumFaces()), -1);
    for (OsdIndex f = 0; f < parent.GetNumFaces(); ++f)
        for (OsdIndex c : parent.GetFaceChildFaces(f))
            if (c >= 0) out[size_t(c)] = f;
    return out;
}

// Marks in `refine` the parents of every face of `level` touching a vertex of `seeds`.
void markParentsAround(const Far::TopologyLevel& level, const std::vector<OsdIndex>& seeds,
                       const std::vector<OsdIndex>& parent, std::vector<uint8_t>& refine) {
    for (OsdIndex v : seeds)
        for (OsdIndex f : level.GetVertexFaces(v)) refine[size_t(parent[size_t(f)])] = 1;
}

}  // namespace

Status planEdits(const InputMesh& mesh, const Topology& topology, const std::string& name, EditRegion& region) {
    const int K = topology.uniformDepth;
    region = EditRegion{};
    region.refine.resize(size_t(K));
    for (int l = 0; l < K; ++l) region.refine[size_t(l)].assign(size_t(topology.level(l).GetNumFaces()), 0);

    // Sites: follow each path down the uniform levels.
    std::vector<std::vector<OsdIndex>> seeds(size_t(K) + 1);  // per level: edited vertices and their neighbours
    for (const auto& edit : mesh.edits) {
        OsdIndex face = OsdIndex(edit.face);
        for (size_t j = 0; j < edit.path.size(); ++j) {
            auto children = topology.level(int(j)).GetFaceChildFaces(face);
            face = children.size() == 4 ? children[edit.path[j]] : -1;
            if (face < 0)
                return Status::error(Status::Internal, name + ": the path of vertex edit " +
                                                           std::to_string(region.sites.size()) + " (" + editName(edit) +
                                                           ") leaves the refined levels");
        }
        EditRegion::Site site;
        site.level = int(edit.path.size());
        const Far::TopologyLevel& level = topology.level(site.level);
        site.vertex = level.GetFaceVertices(face)[edit.vertex];
        region.sites.push_back(site);
        auto& s = seeds[size_t(site.level)];
        s.push_back(site.vertex);
        for (OsdIndex e : level.GetVertexEdges(site.vertex)) s.push_back(otherEnd(level, e, site.vertex));
    }

    // A `set` must be its vertex's only edit.
    std::map<std::pair<int, OsdIndex>, size_t> first;
    for (size_t i = 0; i < region.sites.size(); ++i) {
        auto [it, fresh] = first.emplace(std::make_pair(region.sites[i].level, region.sites[i].vertex), i);
        if (fresh) continue;
        const auto& a = mesh.edits[it->second];
        const auto& b = mesh.edits[i];
        if (a.op == EditOp::Set || b.op == EditOp::Set)
            return Status::error(Status::BadInput,
                                 name + ": vertex edits " + std::to_string(it->second) + " (" + editName(a) + ") and " +
                                     std::to_string(i) + " (" + editName(b) +
                                     ") name the same vertex and one of them is a 'set': their order would decide "
                                     "the result; merge them into one edit");
    }

    // Ref[k-1] from the edits of level k, then the closure towards level 0.
    for (int l = K; l >= 1; --l) {
        const Far::TopologyLevel& level = topology.level(l);
        const std::vector<OsdIndex> parent = parentFaces(topology, l);
        std::vector<OsdIndex> around = seeds[size_t(l)];
        if (l < K) {
            const auto& refine = region.refine[size_t(l)];
            for (OsdIndex f = 0; f < level.GetNumFaces(); ++f)
                if (refine[size_t(f)])
                    for (OsdIndex v : level.GetFaceVertices(f)) around.push_back(v);
        }
        std::sort(around.begin(), around.end());
        around.erase(std::unique(around.begin(), around.end()), around.end());
        markParentsAround(level, around, parent, region.refine[size_t(l) - 1]);
    }
    return Status::ok();
}

Status fillEdits(const InputMesh& mesh, const EditRegion& region, const std::vector<std::vector<uint32_t>>& global,
                 const std::string& name, std::vector<Level>& levels) {
    // Edits ordered by (level, global vertex), input order kept per vertex.
    std::vector<size_t> order(region.sites.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::vector<uint32_t> g(region.sites.size());
    for (size_t i = 0; i < order.size(); ++i) {
        const EditRegion::Site& s = region.sites[i];
        g[i] = size_t(s.level) < global.size() ? global[size_t(s.level)][size_t(s.vertex)] : ~0u;
        if (g[i] == ~0u)
            return Status::error(Status::BadInput, name + ": vertex edit " + std::to_string(i) + " (" +
                                                       editName(mesh.edits[i]) +
                                                       ") names a vertex no patch reads (inside holes?)");
    }
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return std::make_pair(region.sites[a].level, g[a]) < std::make_pair(region.sites[b].level, g[b]);
    });
    for (size_t i : order) {
        VertexEdits& e = levels[size_t(region.sites[i].level)].edits;
        if (e.vertex.empty() || e.vertex.back() != g[i]) {
            if (e.start.empty()) e.start.push_back(0);
            e.vertex.push_back(g[i]);
            e.start.push_back(e.count());
        }
        e.op.push_back(mesh.edits[i].op);
        e.value.insert(e.value.end(), mesh.edits[i].value, mesh.edits[i].value + 3);
        e.start.back() = e.count();
    }
    return Status::ok();
}

}  // namespace lt
