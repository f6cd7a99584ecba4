// StencilOrienter (orient.h).
#include "orient.h"

#include <opensubdiv/far/primvarRefiner.h>

namespace lt {
namespace {

struct Point {
    double p[3] = {0, 0, 0};
    void Clear() { p[0] = p[1] = p[2] = 0; }
    void AddWithWeight(const Point& src, double w) {
        for (int k = 0; k < 3; ++k) p[k] += w * src.p[k];
    }
};

void cross(const double a[3], const double b[3], double n[3]) {
    n[0] = a[1] * b[2] - a[2] * b[1];
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
}

} // namespace

StencilOrienter::StencilOrienter(const Topology& topology, const std::vector<float>& positions)
    : topology_(topology) {
    const int levels = topology.maxLevel() + 1;
    std::vector<std::vector<Point>> pts(static_cast<size_t>(levels));
    pts[0].resize(positions.size() / 3);
    for (size_t i = 0; i < positions.size(); ++i) pts[0][i / 3].p[i % 3] = positions[i];
    for (int l = 1; l < levels; ++l) {
        const Far::TopologyRefiner& refiner = topology.refiner(l - 1);
        pts[size_t(l)].resize(size_t(topology.level(l).GetNumVertices()));
        Point* src = pts[size_t(l) - 1].data();
        Point* dst = pts[size_t(l)].data();
        Far::PrimvarRefinerReal<double>(refiner).Interpolate(topology.local(l - 1) + 1, src, dst);
    }
    points_.resize(size_t(levels));
    for (int l = 0; l < levels; ++l)
        for (const Point& q : pts[size_t(l)]) points_[size_t(l)].insert(points_[size_t(l)].end(), q.p, q.p + 3);
}

void StencilOrienter::orient(int level, OsdIndex face, LimitStencil& s) const {
    if (s.smooth || s.points.empty()) return;
    const std::vector<double>& P = points_[size_t(level)];
    auto at = [&](OsdIndex v) { return &P[size_t(v) * 3]; };
    double tu[3] = {0, 0, 0}, tv[3] = {0, 0, 0};
    const double* c = at(s.points[0]);
    for (size_t k = 1; k < s.points.size(); ++k)
        for (int i = 0; i < 3; ++i) {
            double d = at(s.points[k])[i] - c[i];
            tu[i] += s.tangentU[k] * d;
            tv[i] += s.tangentV[k] * d;
        }
    double n[3], fn[3], e1[3], e2[3];
    cross(tu, tv, n);
    Far::ConstIndexArray fv = topology_.level(level).GetFaceVertices(face);
    for (int i = 0; i < 3; ++i) {
        e1[i] = at(fv[1])[i] - at(fv[0])[i];
        e2[i] = at(fv[2])[i] - at(fv[0])[i];
    }
    cross(e1, e2, fn);
    if (n[0] * fn[0] + n[1] * fn[1] + n[2] * fn[2] < 0)
        for (double& w : s.tangentV) w = -w;
}

} // namespace lt
