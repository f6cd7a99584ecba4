// ipp.vert -- the IPPs of level pc.level (the runtime depth) as flat triangles between
// exact limit points (paper 3.3): vertex 3 f + c is corner c of irregular face f,
// read from the limit pass's output. Corners sit at (s,t) = (0,0), (1,0), (0,1).
// vkCmdDraw(3 * faces); no vertex buffers. LT_CAPTURE: see surface_out.glsl.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "displacement.glsl"
#include "surface_out.glsl"
#include "limit_stencil.glsl"
#include "ipp_eval.glsl"

void main() { evalIppCorner(uint(gl_VertexIndex)); }
