// mesh_clean.cpp -- lt::FaceCleaner (mesh_clean.h): input cleaning shared by the
// OBJ and glTF readers.
#include "mesh_clean.h"

#include <algorithm>
#include <cmath>

namespace lt {

bool zeroAreaTriangle(const float* a, const float* b, const float* c) {
    const float* p[3] = {a, b, c};
    double e[3][3], len2[3];
    for (int k = 0; k < 3; ++k) {
        for (int i = 0; i < 3; ++i) e[k][i] = double(p[(k + 1) % 3][i]) - double(p[k][i]);
        len2[k] = e[k][0] * e[k][0] + e[k][1] * e[k][1] + e[k][2] * e[k][2];
    }
    const double cx = e[0][1] * e[1][2] - e[0][2] * e[1][1];
    const double cy = e[0][2] * e[1][0] - e[0][0] * e[1][2];
    const double cz = e[0][0] * e[1][1] - e[0][1] * e[1][0];
    const double longest = std::max({len2[0], len2[1], len2[2]});
    return std::sqrt(cx * cx + cy * cy + cz * cz) <= 1e-7 * longest;
}

void dropCreasesOfRemovedEdges(InputMesh& mesh, std::vector<uint64_t>& removedEdges, const std::string& name) {
    if (mesh.creases.empty()) return;
    std::sort(removedEdges.begin(), removedEdges.end());
    std::vector<uint64_t> edges;
    edges.reserve(mesh.faces.size());
    for (size_t f = 0; f + 2 < mesh.faces.size(); f += 3)
        for (size_t k = 0; k < 3; ++k) edges.push_back(undirectedEdge(mesh.faces[f + k], mesh.faces[f + (k + 1) % 3]));
    std::sort(edges.begin(), edges.end());
    std::string first;
    auto gone = [&](const InputMesh::Crease& c) {
        const uint64_t e = undirectedEdge(c.a, c.b);
        if (std::binary_search(edges.begin(), edges.end(), e) ||
            !std::binary_search(removedEdges.begin(), removedEdges.end(), e))
            return false;
        if (mesh.cleaning.droppedCreases++ == 0) first = std::to_string(c.a) + "-" + std::to_string(c.b);
        return true;
    };
    mesh.creases.erase(std::remove_if(mesh.creases.begin(), mesh.creases.end(), gone), mesh.creases.end());
    if (const uint32_t n = mesh.cleaning.droppedCreases)
        mesh.warnings.push_back(name + ": " + std::to_string(n) + (n == 1 ? " crease" : " creases") +
                                " dropped: only dropped or repaired faces had its edge (first: edge " + first + ")");
}

FaceCleaner::FaceCleaner(const std::vector<float>& positions, InputCleaning mode)
    : positions_(positions), mode_(mode) {}

// One pass as a stack (a repeat of the top is skipped; a repeat of the one below the
// top pops the top: a spike), then the same rules across the cycle's seam. Each step
// removes a corner, so it is linear. Of two corners at one vertex the earlier stays.
void FaceCleaner::repair(const uint32_t* v, size_t n, std::vector<uint32_t>& corners) const {
    corners.clear();
    for (uint32_t i = 0; i < n; ++i) {
        const size_t m = corners.size();
        if (m >= 1 && v[corners[m - 1]] == v[i]) continue;
        if (m >= 2 && v[corners[m - 2]] == v[i]) {
            corners.pop_back();
            continue;
        }
        corners.push_back(i);
    }
    size_t first = 0;  // the cycle is corners[first ..]
    for (bool changed = true; changed && corners.size() - first >= 2;) {
        const size_t m = corners.size();
        const uint32_t head = v[corners[first]];
        changed = true;
        if (v[corners[m - 1]] == head)
            corners.pop_back();  // .. x | x ..
        else if (m - first >= 3 && v[corners[m - 2]] == head)
            corners.pop_back();  // .. x y | x ..
        else if (m - first >= 3 && v[corners[m - 1]] == v[corners[first + 1]])
            ++first;  // .. x | y x ..
        else
            changed = false;
    }
    corners.erase(corners.begin(), corners.begin() + ptrdiff_t(first));
}

bool FaceCleaner::distinct(const uint32_t* v, const std::vector<uint32_t>& corners) {
    scratch_.clear();
    for (uint32_t c : corners) scratch_.push_back(v[c]);
    std::sort(scratch_.begin(), scratch_.end());
    return std::adjacent_find(scratch_.begin(), scratch_.end()) == scratch_.end();
}

bool FaceCleaner::zeroArea(const uint32_t* v, const std::vector<uint32_t>& corners) const {
    auto at = [&](size_t k) { return &positions_[3 * size_t(v[corners[k]])]; };
    auto samePosition = [&](size_t a, size_t b) {
        return at(a)[0] == at(b)[0] && at(a)[1] == at(b)[1] && at(a)[2] == at(b)[2];
    };
    if (corners.size() == 3 && (samePosition(0, 1) || samePosition(1, 2) || samePosition(2, 0))) return false;
    for (size_t k = 1; k + 1 < corners.size(); ++k)
        if (!zeroAreaTriangle(at(0), at(k), at(k + 1))) return false;
    return true;
}

// The face's cycle from its smallest vertex toward the smaller of that vertex's two
// neighbours names the face in either winding.
bool FaceCleaner::duplicate(const uint32_t* v, const std::vector<uint32_t>& corners, uint64_t tag) {
    const size_t n = corners.size(), at = cycles_.size();
    size_t low = 0;
    for (size_t k = 1; k < n; ++k)
        if (v[corners[k]] < v[corners[low]]) low = k;
    const bool forward = v[corners[(low + 1) % n]] < v[corners[(low + n - 1) % n]];
    uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a, then a finalizer for the low bits
    for (size_t k = 0; k < n; ++k) {
        cycles_.push_back(v[corners[(forward ? low + k : low + n - k) % n]]);
        h = (h ^ cycles_.back()) * 0x100000001b3ull;
    }
    h ^= h >> 33, h *= 0xff51afd7ed558ccdull, h ^= h >> 33;
    if (2 * (hashes_.size() + 1) > slots_.size()) {  // grow: rehash every kept face
        slots_.assign(std::max<size_t>(64, 2 * slots_.size()), 0);
        for (uint32_t f = 0; f < hashes_.size(); ++f) {
            size_t i = hashes_[f] & (slots_.size() - 1);
            while (slots_[i]) i = (i + 1) & (slots_.size() - 1);
            slots_[i] = f + 1;
        }
    }
    size_t i = h & (slots_.size() - 1);
    for (; slots_[i]; i = (i + 1) & (slots_.size() - 1)) {
        const uint32_t f = slots_[i] - 1;
        if (hashes_[f] == h && start_[f + 1] - start_[f] == n &&
            std::equal(cycles_.begin() + ptrdiff_t(at), cycles_.end(), cycles_.begin() + ptrdiff_t(start_[f]))) {
            lastOriginal_ = tags_[f];
            cycles_.resize(at);
            return true;
        }
    }
    slots_[i] = uint32_t(hashes_.size()) + 1;
    start_.push_back(cycles_.size());
    hashes_.push_back(h);
    tags_.push_back(tag);
    return false;
}

FaceCleaner::Fate FaceCleaner::clean(const uint32_t* vertices, size_t n, uint64_t tag, std::vector<uint32_t>& corners) {
    lastRepaired_ = false;
    if (mode_ == InputCleaning::Keep) {
        corners.resize(n);
        for (uint32_t i = 0; i < n; ++i) corners[i] = i;
        return Fate::Kept;
    }
    repair(vertices, n, corners);
    lastRepaired_ = corners.size() != n;
    lastFigureEight_ = corners.size() >= 3;
    Fate fate = Fate::Kept;
    if (corners.size() < 3 || !distinct(vertices, corners))
        fate = Fate::Degenerate;
    else if (zeroArea(vertices, corners))
        return Fate::ZeroArea;
    else if (duplicate(vertices, corners, tag))
        fate = Fate::Duplicate;
    else if (lastRepaired_)
        fate = Fate::Repaired;
    if (fate == Fate::Kept) return fate;
    count(fate, tag);
    if (fate != Fate::Repaired) corners.clear();
    return fate;
}

void FaceCleaner::count(Fate fate, uint64_t tag) {
    uint32_t* counts[] = {nullptr, &report_.repaired, &report_.droppedDegenerate, &report_.droppedZeroArea,
                          &report_.droppedDuplicate};
    uint64_t& first = first_[size_t(fate)];
    if ((*counts[size_t(fate)])++ == 0 || tag < first) {
        first = tag;
        if (fate == Fate::Duplicate) firstOriginal_ = lastOriginal_;
    }
}

std::vector<size_t> FaceCleaner::settleZeroArea(const InputMesh& mesh, const std::vector<Pending>& pending) {
    std::vector<size_t> dropped;
    if (pending.empty()) return dropped;
    std::vector<uint8_t> isPending(mesh.faceCount(), 0);
    for (const Pending& p : pending) std::fill_n(isPending.begin() + p.first, p.count, 1);
    std::vector<uint64_t> edges;  // of the faces of nonzero area
    for (size_t f = 0; f < isPending.size(); ++f)
        for (size_t k = 0; k < 3 && !isPending[f]; ++k)
            edges.push_back(undirectedEdge(mesh.faces[3 * f + k], mesh.faces[3 * f + (k + 1) % 3]));
    std::sort(edges.begin(), edges.end());
    for (size_t i = 0; i < pending.size(); ++i) {
        const Pending& p = pending[i];
        bool sewn = false;
        for (size_t f = p.first; f < p.first + p.count && !sewn; ++f)
            for (size_t k = 0; k < 3 && !sewn; ++k)
                sewn = std::binary_search(edges.begin(), edges.end(),
                                          undirectedEdge(mesh.faces[3 * f + k], mesh.faces[3 * f + (k + 1) % 3]));
        if (sewn && p.repaired) count(Fate::Repaired, p.tag);
        if (sewn) continue;
        count(Fate::ZeroArea, p.tag);
        dropped.push_back(i);
    }
    return dropped;
}

void eraseTriangles(InputMesh& mesh, const std::vector<uint8_t>& drop) {
    const bool uvs = mesh.faceUVs.size() == 2 * mesh.faces.size();
    size_t out = 0;
    for (size_t f = 0; f < drop.size(); ++f) {
        if (drop[f]) continue;
        std::copy_n(&mesh.faces[3 * f], 3, &mesh.faces[3 * out]);
        if (uvs) std::copy_n(&mesh.faceUVs[6 * f], 6, &mesh.faceUVs[6 * out]);
        ++out;
    }
    mesh.faces.resize(3 * out);
    if (uvs) mesh.faceUVs.resize(6 * out);
}

std::string FaceCleaner::defect(Fate fate, const std::function<std::string(uint64_t)>& where) const {
    switch (fate) {
    case Fate::Repaired:
        return "repeats a vertex (refused in strict mode; otherwise the repeats and spikes are removed)";
    case Fate::Degenerate:
        return std::string(lastFigureEight_
                               ? "passes through a vertex twice (a figure-eight)"
                               : "has fewer than 3 distinct vertices once repeats and spikes are removed") +
               " (refused in strict mode; otherwise dropped)";
    case Fate::ZeroArea:
        return "has zero area and shares no edge with a face that has area (refused in strict mode; otherwise "
               "dropped)";
    case Fate::Duplicate:
        return "has the vertices of " + where(lastOriginal_) + " (refused in strict mode; otherwise dropped)";
    case Fate::Kept: break;
    }
    return "";
}

void FaceCleaner::warn(const std::string& prefix, const std::string& noun,
                       const std::function<std::string(uint64_t)>& where, std::vector<std::string>& warnings) const {
    auto line = [&](uint32_t count, Fate fate, const std::string& what, const std::string& first,
                    const std::string& why) {
        if (count == 0) return;
        warnings.push_back(prefix + ": " + std::to_string(count) + " " + what + " (first: " + first + ")" + why);
    };
    auto plural = [&](uint32_t count) { return count == 1 ? noun : noun + "s"; };
    auto first = [&](Fate fate) { return where(first_[size_t(fate)]); };
    const CleaningReport& r = report_;
    line(r.repaired, Fate::Repaired, plural(r.repaired) + " with repeated vertices repaired", first(Fate::Repaired),
         ": repeats and spikes (x y x) removed");
    line(r.droppedDegenerate, Fate::Degenerate, "degenerate " + plural(r.droppedDegenerate) + " dropped",
         first(Fate::Degenerate),
         ": fewer than 3 distinct vertices once repeats and spikes are removed, or a figure-eight");
    line(r.droppedZeroArea, Fate::ZeroArea, plural(r.droppedZeroArea) + " of zero area dropped", first(Fate::ZeroArea),
         ": no edge shared with a face that has area");
    line(r.droppedDuplicate, Fate::Duplicate, "duplicate " + plural(r.droppedDuplicate) + " dropped",
         first(Fate::Duplicate) + ", the vertices of " + where(firstOriginal_), "");
}

}  // namespace lt
