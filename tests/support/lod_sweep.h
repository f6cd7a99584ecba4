// The screen-space level-of-detail sweep, shared by test_lod_sweep.cpp
// (CPU) and test_vulkan_lod.cpp (GPU): views of a mesh from several cameras, at
// several pixel sizes and both spacings, each of whose tessellations must weld bit
// for bit into a surface without cracks or folds.
#pragma once

#include "check_internal.h"  // looptess_check_internal
#include "looptess/runtime.h"

#include <string>
#include <vector>

namespace lt::test {

// Camera 0: in front, 1.6 bounding-box radii from the centre; 1: behind, 4 radii;
// 2: inside the bounding box, a tenth of its size off the centre. 40 degrees, 512 rows.
constexpr int kSweepCameras = 3;

struct SweepView {
    int camera = 0;
    float pixelsPerEdge = 8;
    Spacing spacing = Spacing::Equal;
    std::string name() const;  // "camera 2, 3 px, odd"
};
// Every camera x `pixels` x both spacings.
std::vector<SweepView> sweepViews(const std::vector<float>& pixels);

// Screen mode for `view` of `asset` (tessFactor stays 1: lodTessFactor bounds it).
EvalSettings sweepSettings(const Asset& asset, const SweepView& view);

// The bitwise weld of `soup` (check's weldTessellation): "" when it has no crack (an
// open edge off the control boundary), no edge used three or more times off the
// control mesh's non-manifold edges, no misoriented edge and no non-finite vertex;
// else what it found.
std::string weldFindings(const ControlTopology& topology, const Tessellation& soup);

}  // namespace lt::test
