// Shared by the level-of-detail tests (test_lod.cpp on the CPU, test_vulkan_lod.cpp
// on the GPU): test cameras, a crack check by welding, and IPP recognition.
#pragma once

#include "looptess/runtime.h"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace lt::test {

// Closed corpus shapes and meshes for the crack check.
std::vector<std::string> closedLodMeshes();

// Every control edge has exactly two faces.
bool controlMeshIsClosed(const Asset& asset);

// Test camera `camera` (0: close, looking at the front, 1.6 bounding-box radii from
// the centre; 1: far, from behind, 4 radii), 40 degrees, 512 rows.
EvalSettings lodSettings(const Asset& asset, LodMode mode, int camera, float pixelsPerEdge);
// The same camera with pixelsPerEdge chosen so that lodTessFactor is about `factor`
// (1 < factor < 2^maxDepth).
EvalSettings lodForFactor(const Asset& asset, LodMode mode, int camera, float factor);

// Welds a soup's vertices closer than 2.5e-7 of the bounding-box diagonal (the two
// patches of a shared edge evaluate it in different floating-point orders, about
// 5e-8 apart; the watertight issue will make them bitwise equal) and counts the
// triangles of each welded edge. On a closed surface without T-junctions every edge
// has exactly two. Triangles that the weld collapses (fractional_odd's slivers next
// to a nearly odd factor, collapsed alike from both sides) are counted and skipped;
// unmatched edges shorter than 1e-6 of the diagonal are such slivers that the weld
// cannot resolve (the two sides' rounding is of the same size), counted apart.
struct WeldReport {
    size_t vertices = 0, welded = 0, edges = 0, unmatchedEdges = 0, sliverEdges = 0, degenerate = 0;
    double largestMerge = 0;  // distance between merged vertices, / diagonal
    std::string summary() const;
};
WeldReport weldAndCountEdges(const Tessellation& soup, double diagonal);

// An IPP's base face and the (u,v) of its corners as the evaluator emits them, and
// the same for triangle t of a soup.
std::array<float, 7> ippKey(const PatchParam& param);
std::array<float, 7> triangleKey(const Tessellation& soup, size_t t);

}  // namespace lt::test
