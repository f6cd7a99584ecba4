// How the tests compare a device's tessellation with the CPU evaluator's, so that
// they hold on any conformant Vulkan 1.3 device, not only on lavapipe
// (docs/devices.md says what is bitwise across devices and why):
//
//   what                           compared                    why
//   -----------------------------  --------------------------  ------------------------------
//   order of triangles             in emission order, or as    the tessellator's primitive
//                                  sets of points (Order::Any)  order and triangulation are the
//                                                              implementation's
//   position (undisplaced)         bit for bit                 only + and * without contraction
//   face, (u,v), TEXCOORD_0/1,     bit for bit                 the same
//   COLOR_0
//   normal                         within kNormalRadians       sqrt and / are not correctly
//                                                              rounded in Vulkan
//   TANGENT xyz (w exactly)        within kTangentRadians      the same, after a projection
//   displaced position             within positionTolerance    moved along a unit normal
//
// Order::Any matches each vertex of one side with a vertex of the other at the same
// (base face, u, v) bits, both ways: the same set of points, whatever the order of
// the triangles or the triangulation of a patch, and the same number of triangles.
#pragma once

#include "looptess/runtime.h"

#include <cstddef>
#include <string>

namespace lt::test {

// Bounds on the angle between a device's unit vector and the CPU's.
//
// Normal: the CPU and every device compute the unnormalized normal from the same
// bits (+ and * only), then divide each component by sqrt(n . n). Vulkan allows
// sqrt as inversesqrt (2 ULP) and a reciprocal, and 2.5 ULP for a division; a
// common scale does not turn the vector, so the angle comes from the three
// divisions alone: at most about 2.5 ULP = 3e-7 rad, twice that where a unit vector
// is the input of another one (the IPP corners' limit normals). 1e-6 leaves a margin
// of 1.6x over that and of 12x over what an NVIDIA H200 gave (8e-8 rad).
inline constexpr double kNormalRadians = 1e-6;
// TANGENT: g - n (n . g) with the normal's error, then normalized: the normal's
// error is amplified by |g| / |g in the plane|, which stays below 10 where a tangent
// is defined (g is a combination of the surface's derivatives, in the plane).
inline constexpr double kTangentRadians = 1e-5;

enum class Order {
    Emission,  // triangle k against triangle k, vertex against vertex (our order)
    Any,       // the same set of points at (face, u, v) (the tessellator's order)
};

struct SurfaceMatch {
    Order order = Order::Emission;
    // Largest difference of a position coordinate; 0: bit for bit (undisplaced).
    double positionTolerance = 0;
    double normalRadians = kNormalRadians;
    double tangentRadians = kTangentRadians;
};

struct SurfaceDiff {
    size_t vertices = 0;                                              // of the device's side
    size_t unmatched = 0;                                             // vertices without a partner (Any: no such point)
    size_t positions = 0, normals = 0, tangents = 0, attributes = 0;  // vertices outside
    size_t normalsBitwise = 0;                                        // vertices whose normal is bit for bit the CPU's
    double worstNormal = 0, worstTangent = 0, worstPosition = 0;      // radians, coordinate
    std::string first;                                                // the first difference, in words
    bool sameTriangleCount = true;
    bool ok() const { return sameTriangleCount && unmatched + positions + normals + tangents + attributes == 0; }
    std::string summary() const;
};

// `device` against `cpu` (soups or indexed: each triangle's corners are compared).
SurfaceDiff compareSurfaces(const Tessellation& device, const Tessellation& cpu, const SurfaceMatch& match = {});

// A PLY file of looprender's (--capture: looprender_common.h's writePly; --mesh: position,
// normal, tangent, s t per vertex) as a tessellation, by its properties' names: x y
// z, nx ny nz, face, u v, s t, tx ty tz tw, s1 t1, red green blue alpha (what it
// lacks stays empty; base faces 0 without `face`); indexed where its faces are not
// 3k, 3k+1, 3k+2. `ok` false when the bytes are not such a file.
Tessellation readPly(const std::string& bytes, bool& ok);

// The angle between two vectors of 3 floats (0 when both are zero, pi when only one is).
double angleBetween(const float* a, const float* b);

}  // namespace lt::test
