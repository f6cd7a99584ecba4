// evaluate.comp -- one frame's surface as indexed triangles in an application's
// buffers (vulkan.h, recordEvaluate): the pattern path's vertices, evaluated by the
// same functions as pattern.vert and ipp.vert, so they are the draw's bits.
//
// Output layout (recordEvaluate's, and the CPU evaluator's EvalSettings::indexed):
//
//   vertices  per record in draw order, its pattern's (n + 1)(n + 2) / 2 points row
//             by row: point (i, j) at j (n + 1) - j (j - 1) / 2 + i,
//
//               (0,n)                     row j holds i = 0 .. n - j
//                 |  \
//               (0,1) (1,1) ..
//               (0,0) (1,0) .. (n,0)
//
//             then the IPPs' corners, 3 per IPP triangle;
//   indices   per record its pattern's n^2 triangles, in patterns.h's order (row by
//             row, each cell's up triangle then its down one), then the IPPs' 3 each.
//
// At screen-space factors (LT_FLAG_LOD_SCREEN) each record has the pattern of its own
// edge factors, known only here: the records in record order (list after list, as
// the CPU evaluator), each its pattern's points in its TessDomain's order (the
// uniform ones row by row, as above) and its triangles, then the IPPs.
//
// A dispatch (push constants; specialization LT_SPEC_EVALUATE_KIND picks the kind):
//   PATTERN_POINTS, PATTERN_INDICES  pc.base the record list, pc.level the pattern's
//                n, pc.evaluate = (first vertex, first index, first record, threads)
//   IPPS         pc.level the level, pc.evaluate = (first vertex, first index, first
//                IPP corner, threads); at screen-space factors after the patterns'
//                output (PLACE's totals)
//   at screen-space factors, in this order (barriers between):
//   SORTED_KEYS  as pattern_sort.comp's COUNT (pc.base the list, pc.evaluate.x its
//                records, .y its first chunk's index, .z its first record's over the
//                frame's lists): a work group per chunk; each record and its pattern
//                key into PLACE, each chunk's output sizes too
//   SORTED_SCAN  one work group, pc.evaluate.w the frame's chunks (0: none, global
//                factors), .xy the vertices and indices besides the patterns': the
//                chunks' sizes become their first outputs; the totals into PLACE
//                and the application's counts
//   SORTED_PLACE as SORTED_KEYS: each record's first vertex and index into PLACE
//   SORTED_RECORDS  a work group per record, pc.evaluate.z the first: its pattern's
//                points and indices
// At screen-space factors the application's buffers may hold less than the frame
// (recordEvaluate's room, the bound ranges: .length()): a record that does not fit
// whole, and an IPP corner past either end, is not written; the counts are the
// frame's all the same, so the application sees that it needs more room.
// The keys are computed once (SORTED_KEYS), so the layout cannot disagree with
// itself; the output does not depend on pattern_sort.comp's order. Invocations
// hand each other sums through shared memory only, with one barrier outside any
// loop: a first version with barriers in a loop lost most writes on lavapipe (Mesa
// 22.3; not understood).
#version 450
#extension GL_GOOGLE_include_directive : require
#define LT_EVALUATE
#include "common.glsl"
#include "box_spline.glsl"
#include "displacement.glsl"
#include "surface_out.glsl"
#define LT_WT_VERT
#include "watertight.glsl"
#include "pattern_eval.glsl"
#include "pattern_key.glsl"
#include "limit_stencil.glsl"
#include "ipp_eval.glsl"

layout(local_size_x = LT_LOCAL_SIZE) in;
layout(constant_id = LT_SPEC_EVALUATE_KIND) const uint kKind = LT_EVALUATE_PATTERN_POINTS;

layout(std430, set = 1, binding = 0) writeonly buffer OutVertices {
    float v[];
} outVertices;
layout(std430, set = 1, binding = 1) writeonly buffer OutIndices {
    uint i[];
} outIndices;
layout(std430, set = 1, binding = 2) writeonly buffer OutCounts {
    uint vertices, indices;
} outCounts;
layout(std430, set = 1, binding = 3) readonly buffer PatternTable {
    uint words[];
} patternTable;
// PLACE, at screen-space factors, the SORTED_* kinds' own words (the surface's
// buffer): [0, 2) the frame's pattern vertices and indices; per chunk
// (LT_H_SORT_CHUNKS of them) its first vertex and first index (2 words); per record
// in record order (list after list) the record, its pattern key, its first vertex
// and first index (4 words).
layout(std430, set = 1, binding = 4) buffer Place {
    uint words[];
} place;

uint patternHalf(uint at) { return (patternTable.words[at >> 1] >> (16u * (at & 1u))) & 0xffffu; }

void storeVertex(uint vertex) {
    uint at = LT_EVALUATE_FLOATS * vertex;
    outVertices.v[at] = outPosition.x;
    outVertices.v[at + 1u] = outPosition.y;
    outVertices.v[at + 2u] = outPosition.z;
    outVertices.v[at + 3u] = outNormal.x;
    outVertices.v[at + 4u] = outNormal.y;
    outVertices.v[at + 5u] = outNormal.z;
    outVertices.v[at + 6u] = outTangent.x;
    outVertices.v[at + 7u] = outTangent.y;
    outVertices.v[at + 8u] = outTangent.z;
    outVertices.v[at + 9u] = outTangent.w;
    outVertices.v[at + 10u] = outTexcoord.x;
    outVertices.v[at + 11u] = outTexcoord.y;
}

// The vertices the application's buffer holds (recordEvaluate's room).
uint roomVertices() { return uint(outVertices.v.length()) / LT_EVALUATE_FLOATS; }

uint pointIndex(uint n, uint i, uint j) { return j * (n + 1u) - (j * (j - 1u)) / 2u + i; }

// Pattern `key`'s index count and first index (the sort region's COMMANDS).
uint commandWord(uint key, uint k) { return word(LT_H_SORT) + LT_SORT_COMMAND_WORDS * key + k; }

uint patternVertices(uint key) { return patternTable.words[LT_PT_POINT_COUNT + key]; }
uint patternIndices(uint key) { return word(commandWord(key, 0u)); }

// A chunk work group (SORTED_KEYS, SORTED_PLACE): each invocation takes kPer
// consecutive records [first, end) of the chunk's list.
const uint kPer = LT_SORT_CHUNK / LT_LOCAL_SIZE;
void laneRecords(out uint first, out uint end) {
    first = gl_WorkGroupID.x * LT_SORT_CHUNK + gl_LocalInvocationID.x * kPer;
    end = min(first + kPer, pc.evaluate.x);
}

// Each invocation's (vertices, indices) through shared memory: the sum of the
// invocations before it, and of all. The work group's one barrier.
shared uvec2 sSums[LT_LOCAL_SIZE];
void sharedSums(uvec2 own, out uvec2 before, out uvec2 total) {
    uint lid = gl_LocalInvocationID.x;
    sSums[lid] = own;
    barrier();
    before = uvec2(0u);
    total = uvec2(0u);
    for (uint k = 0u; k < LT_LOCAL_SIZE; ++k) {
        if (k < lid) before += sSums[k];
        total += sSums[k];
    }
}

uint placeWord(uint r) { return 2u + 2u * word(LT_H_SORT_CHUNKS) + 4u * r; }
uvec2 chunkWords(uint chunk) { return uvec2(2u + 2u * chunk, 3u + 2u * chunk); }

void sortedKeys() {
    uint first, end;
    laneRecords(first, end);
    uvec2 own = uvec2(0u);
    for (uint r = first; r < end; ++r) {
        uint record = word(pc.base + r), key = recordKey(record), at = placeWord(pc.evaluate.z + r);
        place.words[at] = record;
        place.words[at + 1u] = key;
        own += uvec2(patternVertices(key), patternIndices(key));
    }
    uvec2 before, total;
    sharedSums(own, before, total);
    if (gl_LocalInvocationID.x == 0u) {
        uvec2 at = chunkWords(pc.evaluate.y + gl_WorkGroupID.x);
        place.words[at.x] = total.x;
        place.words[at.y] = total.y;
    }
}

// Each invocation a range of the chunks: their sizes -> their first outputs.
void sortedScan() {
    uint lid = gl_LocalInvocationID.x, chunks = pc.evaluate.w, per = (chunks + LT_LOCAL_SIZE - 1u) / LT_LOCAL_SIZE;
    uint first = min(lid * per, chunks), end = min(first + per, chunks);
    uvec2 own = uvec2(0u);
    for (uint c = first; c < end; ++c) own += uvec2(place.words[chunkWords(c).x], place.words[chunkWords(c).y]);
    uvec2 next, total;
    sharedSums(own, next, total);
    for (uint c = first; c < end; ++c) {
        uvec2 at = chunkWords(c), size = uvec2(place.words[at.x], place.words[at.y]);
        place.words[at.x] = next.x;
        place.words[at.y] = next.y;
        next += size;
    }
    if (lid == 0u) {
        place.words[0] = total.x;
        place.words[1] = total.y;
        outCounts.vertices = total.x + pc.evaluate.x;
        outCounts.indices = total.y + pc.evaluate.y;
    }
}

void sortedPlace() {
    uint first, end;
    laneRecords(first, end);
    uvec2 own = uvec2(0u);
    for (uint r = first; r < end; ++r) {
        uint key = place.words[placeWord(pc.evaluate.z + r) + 1u];
        own += uvec2(patternVertices(key), patternIndices(key));
    }
    uvec2 before, total;
    sharedSums(own, before, total);
    uvec2 at = chunkWords(pc.evaluate.y + gl_WorkGroupID.x), next = uvec2(place.words[at.x], place.words[at.y]) + before;
    for (uint r = first; r < end; ++r) {
        uint w = placeWord(pc.evaluate.z + r), key = place.words[w + 1u];
        place.words[w + 2u] = next.x;
        place.words[w + 3u] = next.y;
        next += uvec2(patternVertices(key), patternIndices(key));
    }
}

// LT_EVALUATE_SORTED_RECORDS: a work group per record (pc.evaluate.z the
// dispatch's first, in record order over the frame's lists): its pattern's points
// and its indices, where PLACE says.
void sortedRecords() {
    uint lid = gl_LocalInvocationID.x, at = placeWord(pc.evaluate.z + gl_WorkGroupID.x);
    uint record = place.words[at], key = place.words[at + 1u], vertex = place.words[at + 2u], index = place.words[at + 3u];
    uint points = patternVertices(key), count = patternIndices(key);
    if (vertex + points > roomVertices() || index + count > uint(outIndices.i.length())) return;   // no room
    uint point = patternTable.words[LT_PT_POINTS] * 2u + patternTable.words[LT_PT_POINT_FIRST + key];
    for (uint p = lid; p < points; p += LT_LOCAL_SIZE) {
        uint code = patternHalf(point + p), grid = code % LT_PATTERN_GRID_INDICES;
        evalPatternPoint(record, grid % 65u, grid / 65u, 1u << (code / LT_PATTERN_GRID_INDICES));
        storeVertex(vertex + p);
    }
    uint local = LT_PT_LOCAL * 2u + word(commandWord(key, 2u));
    for (uint i = lid; i < count; i += LT_LOCAL_SIZE) outIndices.i[index + i] = vertex + patternHalf(local + i);
}

void main() {
    if (kKind == LT_EVALUATE_SORTED_KEYS) {
        sortedKeys();
        return;
    }
    if (kKind == LT_EVALUATE_SORTED_SCAN) {
        sortedScan();
        return;
    }
    if (kKind == LT_EVALUATE_SORTED_PLACE) {
        sortedPlace();
        return;
    }
    if (kKind == LT_EVALUATE_SORTED_RECORDS) {
        sortedRecords();
        return;
    }
    uint t = gl_GlobalInvocationID.x;
    if (t >= pc.evaluate.w) return;
    uint n = pc.level;
    if (kKind == LT_EVALUATE_IPPS) {   // pc.evaluate.z: the dispatch's first corner
        uvec2 after = (pc.flags & LT_FLAG_LOD_SCREEN) != 0u ? uvec2(place.words[0], place.words[1]) : uvec2(0u);
        uint vertex = after.x + pc.evaluate.x + t, index = after.y + pc.evaluate.y + t;
        if (vertex >= roomVertices() || index >= uint(outIndices.i.length())) return;   // no room (screen-space factors)
        evalIppCorner(pc.evaluate.z + t);
        storeVertex(vertex);
        outIndices.i[index] = vertex;
        return;
    }
    if (kKind == LT_EVALUATE_PATTERN_POINTS) {
        uint points = (n + 1u) * (n + 2u) / 2u;
        uint r = t / points, k = t % points, j = 0u;
        while (k > n - j) {   // row j holds n + 1 - j points
            k -= n + 1u - j;
            ++j;
        }
        evalPatternPoint(word(pc.base + pc.evaluate.z + r), k, j, n);
        storeVertex(pc.evaluate.x + t);
        return;
    }
    // LT_EVALUATE_PATTERN_INDICES: triangle q of record r; row j has n - j up
    // triangles and n - j - 1 down ones, alternating: up(0) down(0) up(1) ..
    uint r = t / (n * n), q = t % (n * n), j = 0u;
    while (q >= 2u * (n - j) - 1u) {
        q -= 2u * (n - j) - 1u;
        ++j;
    }
    uint i = q / 2u;
    uvec3 c = (q & 1u) == 0u ? uvec3(pointIndex(n, i, j), pointIndex(n, i + 1u, j), pointIndex(n, i, j + 1u))
                             : uvec3(pointIndex(n, i + 1u, j), pointIndex(n, i + 1u, j + 1u), pointIndex(n, i, j + 1u));
    uint base = pc.evaluate.x + r * ((n + 1u) * (n + 2u) / 2u);
    outIndices.i[pc.evaluate.y + 3u * t] = base + c.x;
    outIndices.i[pc.evaluate.y + 3u * t + 1u] = base + c.y;
    outIndices.i[pc.evaluate.y + 3u * t + 2u] = base + c.z;
}
