// Private to the baker: which way a limit stencil's normal points.
//
// A stencil with explicit weights takes its tangents from OpenSubdiv's crease or
// corner masks; at a corner sector bounded by two infinitely sharp edges they run
// along those edges, so tu x tv points out of the surface only while the sector
// spans less than 180 degrees. A reflex sector (an L-shaped boundary corner, a
// concave corner where three creases meet on a CAD model) gets the inward normal.
// The orientation is geometry, not topology: StencilOrienter decides it from the
// refined positions of the control mesh being baked.
#pragma once

#include "refine.h"

#include <vector>

namespace lt {

class StencilOrienter {
public:
    // `positions`: 3 per control vertex of the topology's level 0 (unedited: the
    // tables must not depend on edit values, which an application may change).
    StencilOrienter(const Topology& topology, const std::vector<float>& positions);

    // Negates stencil.tangentV when tu x tv, evaluated on the refined positions of
    // `level`, points against the geometric normal of `face` (counter-clockwise
    // corners), the face the stencil is made for. Smooth stencils are left alone.
    void orient(int level, OsdIndex face, LimitStencil& stencil) const;

private:
    const Topology& topology_;
    std::vector<std::vector<double>> points_;  // per level: 3 per vertex
};

} // namespace lt
