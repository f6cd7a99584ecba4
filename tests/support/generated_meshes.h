// Generated test meshes, written by code instead of committed (tests/data/README.md).
#pragma once

#include <cstdint>
#include <string>

namespace lt::test {

// A closed torus (major radius 3, minor 1) of n x n quads, each split into two
// triangles along a diagonal picked at random (std::mt19937(seed)): 2 n^2 triangles,
// n^2 vertices of valences 4..8, about 62% of them extraordinary. OBJ text.
//
//     (i, j+1) d ------ c (i+1, j+1)      diagonal a-c: a b c, a c d
//              |      / |                 diagonal b-d: a b d, b c d
//              |    /   |
//       (i, j) a ------ b (i+1, j)
std::string randomDiagonalTorusObj(int n, uint32_t seed);

// randomDiagonalTorusObj written once per process to the temporary directory; the path.
std::string randomDiagonalTorusFile(int n, uint32_t seed);

}  // namespace lt::test
