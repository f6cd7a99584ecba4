// gpu_layout.h -- the layout of the data the Vulkan path uploads, shared by the GLSL
// shaders (#include "gpu_layout.h") and the C++ that fills the buffers
// (runtime/src/vulkan/gpu_tables.cpp). Only #defines: valid C, C++ and GLSL.
//
// Descriptor set 0 (every stage sees the same four storage buffers):
//   binding 0  tables   uint[]   every baked table, read-only (layout below)
//   binding 1  vertices float[]  3 per global vertex, all levels (asset.h's numbering);
//                                written by the subdivision passes
//   binding 2  limit    float[]  LT_LIMIT_FLOATS (9) per limit stencil of the current depth:
//                                position xyz, unit normal xyz, unit displacement
//                                direction xyz; written by the limit pass. Then, from
//                                float word(LT_H_WT_POINT_RESULTS), the watertight
//                                pass's results (below)
//   binding 3  draw     float[]  DrawPath::Compute: the batch of vertices the compute
//                                evaluation wrote (LT_DRAW_* words each), which
//                                compute.vert draws; a placeholder on other paths
//
// The tables buffer, in 32-bit words. "offset" always means an absolute word index
// into this buffer; floats are stored as their bits (uintBitsToFloat).
//
//   word 0                      global header (LT_H_*)
//   LT_H_SIZE + l * LT_L_SIZE   header of level l = 0..levels-1 (LT_L_*)
//   ...                         the arrays the headers point to
//
// Per level l (level 0 has no refinement: its vertex/edge point counts are 0):
//   VP_PARENT[i]      parent vertex of vertex point i (global index)
//   VP_RING_START[i]  offset of its ring (global indices); count + 1 entries, so the
//                     ring of i is [VP_RING_START[i], VP_RING_START[i + 1])
//   VP_WEIGHTS[i]     offset of its explicit mask (one float per ring entry), or
//                     LT_NONE: smooth rule, ring weight SMOOTH_EDGE[valence]
//   EP_VERTS[4i..]    edge point i: a, b (endpoints), c, d (opposite vertices)
//   EP_WEIGHTS[i]     offset of its (ends, opposite) weight pair, or LT_NONE:
//                     smooth rule (3/8, 1/8)
//   LS_VERTEX[i]      vertex of limit stencil i (global index)
//   LS_RING_START[i]  as VP_RING_START, for the stencil's ring
//   LS_WEIGHTS[i]     offset of n position, n dP/du, n dP/dv weights (n = ring size),
//                     or LT_NONE: Loop's smooth limit masks from SMOOTH_LIMIT
//   IRR_FACES         LT_IRR_WORDS per irregular face (IPP)
//   ED_VERTEX[i]      hierarchical edits (asset.h's VertexEdits): edited vertex i
//                     (global index), increasing
//   ED_START[i]       its first edit in the flat edit order; count + 1 entries, so
//                     its edits are [ED_START[i], ED_START[i + 1])
//
// Global tables:
//   DISPLACEMENT      the optional displacement map's block (LT_D_*), see below
//   PATCHES           LT_PATCH_WORDS per regular patch, all levels, level 0 first
//   SMOOTH_EDGE[n]    float: smooth vertex rule ring weight of valence n
//   SMOOTH_LIMIT[2n]  float bits: smooth limit position weight of valence n;
//   SMOOTH_LIMIT[2n+1] offset of n (dP/du, dP/dv) tangent weight pairs
//   FACE_UVS[6f..]    float: base face f's corner texture coordinates s0 t0 s1 t1
//                     s2 t2 (asset.h's faceUVs), when the asset has TEXCOORD_0
//   FACE_UV1S[6f..]   float: the same for TEXCOORD_1 (faceUV1s), when the asset has it
//   FACE_COLORS[12f..] float: base face f's corner COLOR_0 r g b a (faceColors), when
//                     the asset has it
//   EDIT_OPS[k]       op of flat edit k: 0 set, 1 add, 2 subtract
//   EDIT_VALUES[3k..] float: value of flat edit k. The only words written after the
//                     upload: every recordSubdivision copies them from the surface's
//                     host-visible edit staging (VulkanSurface::setEditValues)
//
// Watertight pass (watertight_sources.comp; spec "Watertight evaluation", "Evaluating
// the sources once per frame"). With LT_FLAG_WATERTIGHT, before the limit pass, one
// thread per point source record k < LT_L_WT_POINT_COUNT of the depth, one per
// normal source record k < LT_L_WT_NORMAL_COUNT and one per root edge
// k < LT_L_WT_ROOT_COUNT (the coarser patch edges that edge roots lie on) evaluate
// them with watertight.glsl's functions into the limit buffer:
//
//   limit[word(LT_H_WT_POINT_RESULTS) + 6k ..]   point source k: position xyz, normal xyz
//   limit[word(LT_H_WT_NORMAL_RESULTS) + 3k ..]  normal source k: normal xyz
//   limit[word(LT_H_WT_ROOT_RESULTS) + 30k ..]   root edge k: its 10 points in its
//                                                canonical frame (phantoms filled)
//
// (normals not unit: the readers unitNormal them). The records are ordered by the
// level of the patches using them, so those of levels <= depth come first.
// patch.tesc hands patch.tese where a patch's corner results are and its rooted
// edges' canonical points (watertight.glsl's interface); limit.comp takes its
// stencils' from them.
//
//   subdivide, edit --> points | normals | roots --> limit --> draws
//
// Draw records (one per drawn 12-point patch; lists per level, addressed by the
// draw's push constant `base`): bits 0..22 the global patch index, then the
// sub-triangle's corners A, B, C as 3-bit domain point ids (see LT_DOMAIN_*):
//   record = patch | A << 23 | B << 26 | C << 29
// GLSL includes this file too (common.glsl): clang-format leaves it as written.
// clang-format off
#ifndef LOOPTESS_GPU_LAYOUT_H
#define LOOPTESS_GPU_LAYOUT_H

#define LT_NONE 0xffffffffu

#define LT_BINDING_TABLES 0
#define LT_BINDING_VERTICES 1
#define LT_BINDING_LIMIT 2
#define LT_BINDING_DRAW 3
#define LT_LIMIT_FLOATS 9   // position, unit normal, unit displacement direction

// Global header.
#define LT_H_LEVELS 0
#define LT_H_PATCHES 1
#define LT_H_SMOOTH_EDGE 2
#define LT_H_SMOOTH_LIMIT 3
#define LT_H_DISPLACEMENT 4  // offset of the displacement block (LT_D_*, below), or LT_NONE
#define LT_H_EDIT_OPS 5      // offset of EDIT_OPS (one word per edit, flat order)
#define LT_H_EDIT_VALUES 6   // offset of EDIT_VALUES (3 floats per edit, flat order)
#define LT_H_WT_POINTS 7     // offset of the point source records (LT_WT_POINT_WORDS each)
#define LT_H_WT_NORMALS 8    // offset of the normal source records (LT_WT_NORMAL_WORDS each)
#define LT_H_WT_POINT_RESULTS 9   // limit buffer float index of point source 0's results
#define LT_H_WT_NORMAL_RESULTS 10 // limit buffer float index of normal source 0's result
#define LT_H_WT_ROOTS 11      // offset of the edge root records (LT_WT_ROOT_WORDS each)
#define LT_H_WT_ROOT_RESULTS 12   // limit buffer float index of root edge 0's points
#define LT_H_WT_ROOT_EDGES 13     // offset of the root edges (LT_WT_ROOT_EDGE_WORDS each)
#define LT_H_FACE_UVS 14     // offset of FACE_UVS, or LT_NONE (the asset has no TEXCOORD_0)
#define LT_H_FACE_UV1S 15    // offset of FACE_UV1S, or LT_NONE
#define LT_H_FACE_COLORS 16  // offset of FACE_COLORS, or LT_NONE
#define LT_H_SORT_RECORDS 17   // offset of the sort region's RECORDS (below; COMMANDS at word LT_H_SORT)
#define LT_H_SORT_COUNTS 18    // offset of its COUNTS
#define LT_H_SORT_CHUNKS 19    // chunks a frame sorts at most: the row length of COUNTS
#define LT_H_SORT 20           // offset of the sort region (its COMMANDS)
#define LT_H_SIZE 21

// Level header fields.
#define LT_L_FIRST_VERTEX 0
#define LT_L_VP_COUNT 1
#define LT_L_VP_PARENT 2
#define LT_L_VP_RING_START 3
#define LT_L_VP_WEIGHTS 4
#define LT_L_EP_COUNT 5
#define LT_L_EP_VERTS 6
#define LT_L_EP_WEIGHTS 7
#define LT_L_LS_COUNT 8
#define LT_L_LS_VERTEX 9
#define LT_L_LS_RING_START 10
#define LT_L_LS_WEIGHTS 11
#define LT_L_IRR_COUNT 12
#define LT_L_IRR_FACES 13
#define LT_L_LS_WT 14       // 4 words per limit stencil: point source index k or LT_NONE,
                            // stencil (local) whose position it takes, normal source
                            // index k or LT_NONE, level 0's stencil whose normal it
                            // takes or LT_NONE (watertight.h, rules 3, 4, 4b)
#define LT_L_ED_COUNT 15    // edited vertices of this level (0: no edit pass)
#define LT_L_ED_VERTEX 16
#define LT_L_ED_START 17
#define LT_L_WT_POINT_COUNT 18   // point source records the levels <= this one use (a prefix)
#define LT_L_WT_NORMAL_COUNT 19  // normal source records the levels <= this one use (a prefix)
#define LT_L_WT_ROOT_COUNT 20    // root edges the levels <= this one use (a prefix)
#define LT_L_SIZE 21

// A regular patch: 12 point indices (asset.h's order), then:
#define LT_PATCH_INFO 12    // boundaryMask | level << 8 | rotated << 16
#define LT_PATCH_FACE 13    // base face
#define LT_PATCH_UV 14      // ui | vi << 16
#define LT_PATCH_SPLIT 15   // offset of the patch's LT_SPLIT_WORDS, or LT_NONE (no split edge)
#define LT_PATCH_WT 16      // watertight (runtime/internal/watertight.h): 3 words, corner i's point
                            // source (its index k, not its offset); then the offset of the
                            // patch's LT_WT_EXTRA_WORDS or LT_NONE (when all six are LT_NONE)
#define LT_PATCH_WT_BITS 20 // LT_WT_BIT_* << edge i, for i = 0, 1, 2
#define LT_PATCH_WORDS 21
// Bits of LT_PATCH_WT_BITS (shifted left by the edge): the edge is flipped (its
// canonical x = 1 - local); a boundary or sharp edge of this patch; its source edge
// (the root's, else this one) is one (edgeCubic); it has a root.
#define LT_WT_BIT_FLIP 1u
#define LT_WT_BIT_SHARP 8u
#define LT_WT_BIT_CREASE 64u
#define LT_WT_BIT_ROOT 512u
// A patch's watertight extras: edge i's root (its index k) or LT_NONE (its own edge)
// at 0 + i, corner i's normal source (its index k) or LT_NONE (rule 4) at 3 + i.
#define LT_WT_EXTRA_WORDS 6
// Watertight records, words: point source = global patch, edge, x (float bits);
// edge root = its root edge's index, offset, scale (float bits); root edge = global
// patch, edge; normal source = global patch, corner. Point source k is at
// word(LT_H_WT_POINTS) + 3k, normal source k at word(LT_H_WT_NORMALS) + 2k, edge root
// k at word(LT_H_WT_ROOTS) + 3k, root edge k at word(LT_H_WT_ROOT_EDGES) + 2k.
#define LT_WT_POINT_WORDS 3
#define LT_WT_ROOT_WORDS 3
#define LT_WT_ROOT_EDGE_WORDS 2
#define LT_WT_NORMAL_WORDS 2
// Floats of one point / normal source's results in the limit buffer (watertight pass).
#define LT_WT_POINT_FLOATS 6
#define LT_WT_NORMAL_FLOATS 3
#define LT_WT_ROOT_FLOATS 30
// The level l+1 vertices of a patch's split edges (screen-space LOD, runtime/internal/lod.h):
// vertex point of corner i at 0 + i, edge point of edge i at 3 + i; LT_NONE for the
// edges that are not split.
#define LT_SPLIT_WORDS 6

// An irregular face: 3 limit stencil indices (local to its level), then:
#define LT_IRR_FACE 3       // base face
#define LT_IRR_UV 4         // ui | vi << 16
#define LT_IRR_INFO 5       // level << 8 | rotated << 16 (as LT_PATCH_INFO, mask 0)
#define LT_IRR_WORDS 6

// --- Displacement map (optional; asset.h's DisplacementMap, spec "Displacement map";
// read by displacement.glsl). At word(LT_H_DISPLACEMENT), when not LT_NONE:
//   LT_D_RESOLUTION   R, a power of two 1..64
//   LT_D_SCALE        float bits of scale
//   LT_D_BIAS         float bits of bias
//   LT_D_VERTICES     V: the control vertex count (= the first interior sample)
//   LT_D_EDGE_BASE    index of the first edge sample, V + F (R-1)(R-2)/2
//   LT_D_FACES        offset of LT_D_FACE_WORDS words per base face f:
//                       c0 c1 c2 (control vertices, asset.faces), e0 e1 e2 (faceEdges)
//   LT_D_SAMPLES      offset of the samples (the format's order), two 16-bit samples
//                     per word: sample k is bits 16 (k & 1) .. +15 of word k >> 1
// Sample indices fit 32 bits (buildGpuTables refuses more samples).
#define LT_D_RESOLUTION 0
#define LT_D_SCALE 1
#define LT_D_BIAS 2
#define LT_D_VERTICES 3
#define LT_D_EDGE_BASE 4
#define LT_D_FACES 5
#define LT_D_SAMPLES 6
#define LT_D_SIZE 7
#define LT_D_FACE_WORDS 6

// Draw records.
#define LT_RECORD_PATCH_BITS 23
#define LT_RECORD_PATCH_MASK 0x7fffffu
// Domain point ids of a patch's sub-triangle corners, in the patch's (s,t):
//   0 C0 (0,0)  1 C1 (1,0)  2 C2 (0,1)  3 M0 (1/2,0)  4 M1 (1/2,1/2)  5 M2 (0,1/2)
#define LT_DOMAIN_M0 3

// Push constants (one block for every stage; std430 offsets in bytes):
//   mat4 mvp (0), vec4 light (64), float tessFactor (80), uint level (84),
//   uint base (88), uint flags (92, LT_FLAG_*; draws and the limit pass), vec4 lod (96: eye xyz, scale k;
//   LT_FLAG_LOD_SCREEN draws only), uvec4 evaluate (112: evaluate.comp's first output
//   vertex, first output index, first record and thread count). 128 bytes: the least
//   maxPushConstantsSize a device has.
#define LT_PUSH_CONSTANT_SIZE 128
// Refinement patterns (runtime/internal/patterns.h, DrawPath::Patterns). One per edge
// factor combination (e0, e1, e2), each a power of two 1..64: pattern key
// log2(e0) * 49 + log2(e1) * 7 + log2(e2) (tessellator edge order, patch.tese).
// Their indices name points of the grid of the largest factor N = 2^c: c * 4225 +
// j * 65 + i (pattern.vert), so 16 bits hold them.
#define LT_PATTERN_KEYS 343
#define LT_PATTERN_GRID_INDICES 4225
// Screen-space factors on the pattern path (pattern_sort.comp). At word
// LT_H_SORT of the tables, a region the sort pass rewrites every frame:
//   COMMANDS  LT_PATTERN_KEYS VkDrawIndexedIndirectCommands (5 words: index count,
//             instance count, first index, vertex offset, first instance); index
//             count, first index and vertex offset written at upload
//   RECORDS   the frame's drawn records sorted by pattern key (stable): pattern
//             k's are [first instance, + instance count), pattern.vert's list
//   COUNTS    LT_PATTERN_KEYS rows of LT_H_SORT_CHUNKS words: records of key k in
//             chunk c (a chunk: LT_SORT_CHUNK consecutive records of one list),
//             then that chunk's first slot for key k in RECORDS
#define LT_SORT_COMMAND_WORDS 5
#define LT_SORT_LOCAL_SIZE 128
#define LT_SORT_CHUNK 1024
// pattern_sort.comp's passes (push constant `level`).
#define LT_SORT_COUNT 0u
#define LT_SORT_SCAN 1u
#define LT_SORT_SCATTER 2u
// Patch classes (paper Fig. 7), in the style value the draws hand to shade.frag.
#define LT_CLASS_RPP 0u  // regular patch drawn whole
#define LT_CLASS_NPP 1u  // sub-triangle of a non-plain patch
#define LT_CLASS_IPP 2u  // irregular face drawn as a flat triangle

// Bits of the push constant `flags`.
#define LT_FLAG_COLOR_LEVELS 1u  // shade.frag colours by level and patch class
#define LT_FLAG_LOD_SCREEN 2u    // patch.tesc: per-edge screen-space factors, tessFactor = their bound F
#define LT_FLAG_WATERTIGHT 4u    // limit.comp: watertight evaluation (watertight.glsl); set on the
                                 // draws too, whose pipelines have LT_SPEC_WATERTIGHT exactly then
                                 // (the shaders test the constant) and need the watertight pass's results
#define LT_FLAG_DISPLACE 8u      // patch.tese, ipp.vert: displace by the asset's map, if any
#define LT_FLAG_FACETED 16u      // shade.frag: normals from the drawn triangles (displaced surfaces)
#define LT_FLAG_FRACTIONAL_ODD 32u  // patch.tesc: fractional-odd spacing (sub_patches.h's snapOddFactor)
#define LT_FLAG_COLOR_TEXCOORDS 64u // shade.frag colours by TEXCOORD_0 (a checker of 8 x 8 texels a unit)

// Specialization constant ids of the draw pipelines (common.glsl, pipelines.cpp).
#define LT_SPEC_WATERTIGHT 0  // bool: the pipeline evaluates watertight (draws with LT_FLAG_WATERTIGHT)
#define LT_SPEC_DISPLACE 1    // bool: the pipeline can displace (LT_FLAG_DISPLACE)
#define LT_SPEC_TANGENT 2     // bool: the pipeline emits TANGENT (surface_out.glsl)
#define LT_SPEC_ATTRIBUTES 3  // bool: the pipeline emits base face, (u,v), TEXCOORD_1 and COLOR_0
#define LT_SPEC_EVALUATE_KIND 4  // uint, evaluate.comp: LT_EVALUATE_* below
#define LT_SPEC_EVALUATE_LAYOUT 5  // uint, evaluate.comp: what a vertex is, LT_LAYOUT_* below

// What an evaluate.comp dispatch writes (vulkan.h's recordEvaluate).
#define LT_EVALUATE_PATTERN_POINTS 0u   // a thread per pattern point of each record: a vertex
#define LT_EVALUATE_PATTERN_INDICES 1u  // a thread per pattern triangle of each record: 3 indices
#define LT_EVALUATE_IPPS 2u             // a thread per IPP corner: a vertex and its index
// Screen-space factors (records sorted by pattern_sort.comp, their patterns known
// only on the GPU):
#define LT_EVALUATE_SORTED_KEYS 3u      // a work group per chunk: each record's pattern, the chunk's sizes
#define LT_EVALUATE_SORTED_SCAN 4u      // one work group: each chunk's first output, the counts
#define LT_EVALUATE_SORTED_PLACE 5u     // a work group per chunk: each record's first output
#define LT_EVALUATE_SORTED_RECORDS 6u   // a work group per record: its vertices and indices
// DrawPath::Compute at screen-space factors: after KEYS, SCAN and PLACE, the frame
// cut into batches that fit the surface's buffer (compute_path.cpp's diagram):
#define LT_EVALUATE_BATCHES 7u          // a thread per record and IPP triangle: where each batch starts
#define LT_EVALUATE_BATCH_ARGS 8u       // a thread per batch: its dispatch and draw commands
#define LT_EVALUATE_BATCH_POINTS 9u     // a thread per vertex of a batch (indirect): a vertex
#define LT_EVALUATE_BATCH_INDICES 10u   // a thread per index of a batch's records (indirect): an index
// Words per batch in the batch table: its first item (records, then IPP triangles),
// first vertex and first index in the frame. Its commands: a VkDispatchIndirectCommand
// for BATCH_POINTS (3 words), one for BATCH_INDICES (3), a VkDrawIndexedIndirectCommand (5).
#define LT_BATCH_WORDS 3
#define LT_BATCH_COMMAND_WORDS 11
// The most vertices one record's pattern has (N = 64: 65 * 66 / 2).
#define LT_MAX_RECORD_VERTICES 2145u
// The pattern table of evaluate.comp (set 1, binding 3; draw_plan.h's PatternLibrary),
// in words:
//   [0, 343)     first point of pattern k in POINTS (16-bit units)
//   [343, 686)   points of pattern k
//   686          offset of POINTS (words)
//   LOCAL        from word LT_PT_LOCAL: every pattern's indices as the pattern index
//                buffer has them (16 bits each, two a word, low half first), but
//                naming the pattern's own points (its TessDomain's order)
//   POINTS       each pattern's points in that order, as grid indices (16 bits:
//                c * 4225 + j * 65 + i, pattern.vert's encoding)
#define LT_PT_POINT_FIRST 0
#define LT_PT_POINT_COUNT 343
#define LT_PT_POINTS 686
#define LT_PT_LOCAL 687
// What a vertex an evaluation writes is (LT_SPEC_EVALUATE_LAYOUT):
//   LT_LAYOUT_APPLICATION  recordEvaluate's, LT_EVALUATE_FLOATS floats: position xyz,
//                          unit normal xyz, TANGENT xyzw (0 0 0 1 without TEXCOORD_0),
//                          TEXCOORD_0 s t (0 0 without)
//   LT_LAYOUT_DRAW         DrawPath::Compute's, read back by compute.vert, in words:
//                          0 position xyz, 3 unit normal xyz, 6 TEXCOORD_0 s t,
//                          8 style (uint: level | class << 8), then with
//                          kSpecTangent TANGENT xyzw, then with kSpecAttributes base
//                          face (uint), u v, TEXCOORD_1 s t, COLOR_0 r g b a
#define LT_LAYOUT_APPLICATION 0u
#define LT_LAYOUT_DRAW 1u
#define LT_EVALUATE_FLOATS 12
#define LT_DRAW_BASE_WORDS 9
#define LT_DRAW_TANGENT_WORDS 4
#define LT_DRAW_ATTRIBUTE_WORDS 9
// Words of a draw vertex with the given specialization (bools as 0 or 1).
#define LT_DRAW_WORDS(tangent, attributes) \
    (LT_DRAW_BASE_WORDS + (tangent) * LT_DRAW_TANGENT_WORDS + (attributes) * LT_DRAW_ATTRIBUTE_WORDS)

// Hierarchical edit operations (asset.h's EditOp).
#define LT_EDIT_SET 0u
#define LT_EDIT_ADD 1u
#define LT_EDIT_SUBTRACT 2u

// Compute work-group size of the subdivision, edit, limit and watertight passes.
#define LT_LOCAL_SIZE 64

// Transform feedback record of one captured vertex: position xyz, unit normal xyz,
// base face (uint), u, v, TEXCOORD_0 s t (0 0 without FACE_UVS), TANGENT xyzw
// (0 0 0 1 without FACE_UVS or LT_SPEC_TANGENT), TEXCOORD_1 s t (0 0 without
// FACE_UV1S), COLOR_0 r g b a (1 1 1 1 without FACE_COLORS). Bytes.
#define LT_CAPTURE_STRIDE 84

// clang-format on
#endif
