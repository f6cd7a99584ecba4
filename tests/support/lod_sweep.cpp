// The screen-space level-of-detail sweep (see lod_sweep.h).
#include "lod_sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lt::test {

std::string SweepView::name() const {
    char px[16];
    std::snprintf(px, sizeof px, "%g", pixelsPerEdge);
    return "camera " + std::to_string(camera) + ", " + px + " px, " + (spacing == Spacing::Equal ? "equal" : "odd");
}

std::vector<SweepView> sweepViews(const std::vector<float>& pixels) {
    std::vector<SweepView> views;
    for (int camera = 0; camera < kSweepCameras; ++camera)
        for (float px : pixels)
            for (Spacing spacing : {Spacing::Equal, Spacing::FractionalOdd}) views.push_back({camera, px, spacing});
    return views;
}

EvalSettings sweepSettings(const Asset& asset, const SweepView& view) {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < asset.positions.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], asset.positions[i]);
        hi[i % 3] = std::max(hi[i % 3], asset.positions[i]);
    }
    const double dirs[kSweepCameras][3] = {{0.3, 0.2, 1.0}, {-1.0, 0.5, -0.4}, {0.5, -0.3, 0.2}};
    const double* d = dirs[view.camera];
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double size[3], radius = 0;
    for (int k = 0; k < 3; ++k) size[k] = double(hi[k]) - lo[k], radius += size[k] * size[k];
    radius = 0.5 * std::sqrt(radius);
    float eye[3];
    for (int k = 0; k < 3; ++k) {
        const double centre = 0.5 * (double(lo[k]) + hi[k]);
        eye[k] = float(view.camera == 2 ? centre + 0.1 * size[k] * d[k] / len
                                        : centre + d[k] / len * (view.camera == 0 ? 1.6 : 4.0) * radius);
    }
    EvalSettings es;
    es.spacing = view.spacing;
    es.lod = cameraLod(LodMode::Screen, eye, 40.0f, 512, view.pixelsPerEdge);
    return es;
}

std::string weldFindings(const ControlTopology& topology, const Tessellation& soup) {
    WeldResult w;
    weldTessellation(soup, topology, w);
    if (w.pass()) return "";
    return std::to_string(w.crackEdges) + " open edges off the control boundary (" + std::to_string(w.tJunctions) +
           " T-junctions), " + std::to_string(w.unexpectedNonManifoldEdges) +
           " edges used three or more times off non-manifold control edges, " + std::to_string(w.misorientedEdges) +
           " misoriented edges, " + std::to_string(w.nonFiniteVertices) + " non-finite vertices; " +
           std::to_string(w.triangles) + " triangles, " + std::to_string(w.weldedVertices) + " welded vertices";
}

}  // namespace lt::test
