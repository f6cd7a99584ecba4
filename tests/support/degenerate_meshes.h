// Small generated meshes where the Loop limit surface has no tangent plane, or
// comes close to having none: the degenerate corners of the spec's "Faces without
// a tangent plane" (tests/check/test_degenerate_hunt.cpp bakes and checks them).
#pragma once

#include <cstdint>
#include <string>

namespace lt::test {

// One generated mesh: OBJ text (with OpenSubdiv `t crease` tags where it has
// creases) and a name saying its kind, seed and index (a file name stem).
struct DegenerateMesh {
    std::string name;
    std::string obj;
};

// How many kinds of mesh the hunt generates (below).
constexpr uint32_t kDegenerateKinds = 6;

// Mesh `index` of the hunt with `seed`: a function of both alone, the same on every
// machine (a 64-bit LCG, no std distributions). Kinds, by index % 6, each with a
// random size, bumps, rotation, scale (10^-2 .. 10^2) and offset (up to 10 sizes):
//
//   0 pinch      two fans (3..6 faces, open or closed) sharing their centre, their
//                rings waved so their corners may turn over as they are refined
//   1 slit       an open fan of 3..7 faces round its centre whose two end spokes
//                coincide (a slit) or end 1e-3 .. 1e-7 apart (a near-slit),
//                sometimes with an outer strip
//   2 corner     a closed fan of 4..8 faces whose centre has three infinitely sharp
//                spokes; one sector is flat and may span more than 180 degrees
//   3 book       3 or 4 pages of one or two triangles on one edge (non-manifold)
//   4 wide fan   an open fan of 6..10 faces (a boundary sector with no tangent
//                plane by topology), sometimes with a crease
//   5 sheets     a grid with a fin of 2..4 faces on two edges of its centre, a
//                non-manifold vertex whose sheets are crease sectors of 1..5 faces
DegenerateMesh degenerateMesh(uint64_t seed, uint32_t index);

}  // namespace lt::test
