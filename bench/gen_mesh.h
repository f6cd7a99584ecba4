// bench/gen_mesh.h -- the benchmark's generated control mesh and small mesh
// statistics. Deterministic: no time, no environment, no std::rand.
#pragma once

#include "looptess/tools/baker.h"

#include <cstdint>
#include <string>

namespace ltbench {

// Parameters of the generated closed mesh (a perturbed torus, see makeTorus).
struct TorusParams {
    uint32_t around = 250;        // grid cells around the major circle (>= 3)
    uint32_t across = 200;        // grid cells around the tube (>= 3)
    uint32_t flipOneIn = 64;      // each cell's diagonal is flipped with probability 1/flipOneIn
    float noise = 0.02f;          // tube radius is scaled by 1 + noise * (x - 0.5), x in [0, 1)
    uint64_t seed = 0x5eed100cu;  // LCG seed
};

// A closed genus-1 triangle mesh: an around x across grid on a torus (major radius
// 1, tube radius 0.35), every cell split into two counter-clockwise triangles
// (normals point outwards) along the same diagonal, so every vertex has valence 6.
// A fixed-seed 64-bit LCG (Knuth's MMIX constants) then, per cell in row order,
// flips the cell's diagonal with probability 1/flipOneIn (its two diagonal ends
// lose an edge, the other two gain one: valence 5 and 7 extraordinary vertices,
// 4 and 8 where flips touch) and, per vertex, scales its tube radius by
// 1 + noise * (x - 0.5). 2 * around * across triangles, around * across vertices.
// The result passes lt::checkInput; same params, same mesh.
lt::InputMesh makeTorus(const TorusParams& params = TorusParams{});

// The scan-like mesh of the memory-at-scale figures (bench/README.md): a 1000 x 500
// cell torus, every other diagonal flipped on average, so about half the vertices
// are extraordinary. 1,000,000 triangles, 500,000 vertices.
TorusParams scanParams();

// The bench's generated meshes by name: "torus" (TorusParams{}) and "scan1m"
// (scanParams()); false for another name.
bool generatedParams(const std::string& name, TorusParams& params);

// Vertices whose valence (number of distinct neighbours) is not the regular one:
// 6 inside, 4 on a boundary. Counts every vertex of a non-manifold mesh that way
// too; for reports only.
uint32_t countExtraordinary(const lt::InputMesh& mesh);

}  // namespace ltbench
