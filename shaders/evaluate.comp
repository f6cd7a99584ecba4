// evaluate.comp -- one frame's surface as indexed triangles in an application's
// buffers (vulkan.h, recordEvaluate), or in DrawPath::Compute's batch buffer, which
// compute.vert draws (runtime/src/vulkan/compute_path.h): the pattern path's
// vertices, evaluated by the same functions as pattern.vert and ipp.vert, so they
// are the draw's bits. LT_SPEC_EVALUATE_LAYOUT says what a vertex holds
// (gpu_layout.h's LT_LAYOUT_*).
//
// Output layout (recordEvaluate's, and the CPU evaluator's EvalSettings::indexed):
//
//   vertices  per record in draw order, its pattern's (n + 1)(n + 2) / 2 points row
//             by row: point (i, j) at j (n + 1) - j (j - 1) / 2 + i,
//
//               (0,n)                     row j holds i = 0 .. n - j
//                 |  \  .
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
//   BATCHES, BATCH_ARGS, BATCH_POINTS, BATCH_INDICES  DrawPath::Compute's batches at
//                screen-space factors, after PLACE (below, "the frame in batches")
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
layout(constant_id = LT_SPEC_EVALUATE_LAYOUT) const uint kLayout = LT_LAYOUT_APPLICATION;

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

// Words a vertex takes in the output (gpu_layout.h's LT_LAYOUT_*).
uint vertexWords() {
    return kLayout == LT_LAYOUT_APPLICATION ? LT_EVALUATE_FLOATS : LT_DRAW_WORDS(uint(kSpecTangent), uint(kSpecAttributes));
}

void storeVertex(uint vertex) {
    uint at = vertexWords() * vertex;
    outVertices.v[at] = outPosition.x;
    outVertices.v[at + 1u] = outPosition.y;
    outVertices.v[at + 2u] = outPosition.z;
    outVertices.v[at + 3u] = outNormal.x;
    outVertices.v[at + 4u] = outNormal.y;
    outVertices.v[at + 5u] = outNormal.z;
    if (kLayout == LT_LAYOUT_APPLICATION) {
        outVertices.v[at + 6u] = outTangent.x;
        outVertices.v[at + 7u] = outTangent.y;
        outVertices.v[at + 8u] = outTangent.z;
        outVertices.v[at + 9u] = outTangent.w;
        outVertices.v[at + 10u] = outTexcoord.x;
        outVertices.v[at + 11u] = outTexcoord.y;
        return;
    }
    outVertices.v[at + 6u] = outTexcoord.x;
    outVertices.v[at + 7u] = outTexcoord.y;
    outVertices.v[at + 8u] = uintBitsToFloat(outStyle);
    at += LT_DRAW_BASE_WORDS;
    if (kSpecTangent) {
        outVertices.v[at] = outTangent.x;
        outVertices.v[at + 1u] = outTangent.y;
        outVertices.v[at + 2u] = outTangent.z;
        outVertices.v[at + 3u] = outTangent.w;
        at += LT_DRAW_TANGENT_WORDS;
    }
    if (kSpecAttributes) {
        outVertices.v[at] = uintBitsToFloat(outFace);
        outVertices.v[at + 1u] = outUV.x;
        outVertices.v[at + 2u] = outUV.y;
        outVertices.v[at + 3u] = outTexcoord1.x;
        outVertices.v[at + 4u] = outTexcoord1.y;
        outVertices.v[at + 5u] = outColor.x;
        outVertices.v[at + 6u] = outColor.y;
        outVertices.v[at + 7u] = outColor.z;
        outVertices.v[at + 8u] = outColor.w;
    }
}

// The vertices the output buffer holds (recordEvaluate's room, or a batch's).
uint roomVertices() { return uint(outVertices.v.length()) / vertexWords(); }

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

// ---- DrawPath::Compute at screen-space factors: the frame in batches -------------
// After SORTED_PLACE each record knows its first vertex and index in the frame, and
// the IPP triangles follow the records' outputs. An item (a record, then an IPP
// triangle, in output order) belongs to batch floor(first vertex / pc.evaluate.z):
//
//   frame's vertices   |rec|rec|..|rec| rec |..|ipp|ipp|..|
//   batch boundaries   0           Cp         2 Cp         (Cp = pc.evaluate.z)
//   batch k            the items whose first vertex is in [k Cp, (k + 1) Cp)
//
// so a batch holds less than Cp + LT_MAX_RECORD_VERTICES vertices (the room the
// surface gives it) and fewer than 6 times as many indices (a pattern has fewer than
// 6 a vertex, an IPP 1). Its vertices and indices are written from 0 of the batch
// buffers: an item's outputs less its batch's first ones, a thread per vertex and
// one per index (BATCH_POINTS, BATCH_INDICES), each finding its record by a binary
// search over the batch's records' first outputs.
//   pc.base      the batch table's first word in PLACE: per batch k <= K its first item,
//                vertex and index in the frame (LT_BATCH_WORDS; entry K: the frame's
//                end), then per batch k < K its commands (LT_BATCH_COMMAND_WORDS)
//   pc.evaluate  (records, IPP triangles, Cp or batch k, batches K)

uint itemCount() { return pc.evaluate.x + pc.evaluate.y; }
uvec2 itemFirst(uint item) {
    if (item < pc.evaluate.x) {
        uint at = placeWord(item);
        return uvec2(place.words[at + 2u], place.words[at + 3u]);
    }
    uint t = item - pc.evaluate.x;
    return uvec2(place.words[0] + 3u * t, place.words[1] + 3u * t);
}
uint batchWord(uint k) { return pc.base + LT_BATCH_WORDS * k; }
// Batch k's first vertex and index in the frame (its outputs' origin in the buffer).
uvec2 batchOrigin(uint k) { return uvec2(place.words[batchWord(k) + 1u], place.words[batchWord(k) + 2u]); }
void setBatch(uint k, uint item, uvec2 first) {
    place.words[batchWord(k)] = item;
    place.words[batchWord(k) + 1u] = first.x;
    place.words[batchWord(k) + 2u] = first.y;
}

// LT_EVALUATE_BATCHES: a thread per item (pc.level the dispatch's first); the item
// that starts batches writes their entries, the last item the end's.
void batches() {
    uint item = pc.level + gl_GlobalInvocationID.x, n = itemCount(), last = pc.evaluate.w;
    uvec2 end = uvec2(place.words[0] + 3u * pc.evaluate.y, place.words[1] + 3u * pc.evaluate.y);
    if (n == 0u) {
        if (item == 0u)
            for (uint k = 0u; k <= last; ++k) setBatch(k, 0u, end);
        return;
    }
    if (item >= n) return;
    uvec2 first = itemFirst(item);
    uint b = min(first.x / pc.evaluate.z, last - 1u);
    uint from = item == 0u ? 0u : min(itemFirst(item - 1u).x / pc.evaluate.z, last - 1u) + 1u;
    for (uint k = from; k <= b; ++k) setBatch(k, item, first);
    if (item == n - 1u)
        for (uint k = b + 1u; k <= last; ++k) setBatch(k, n, end);
}

// LT_EVALUATE_BATCH_ARGS: a thread per batch: a thread per vertex of its points,
// one per index of its records (the IPPs' indices come with their vertices), and
// its draw.
void batchArgs() {
    uint k = gl_GlobalInvocationID.x;
    if (k >= pc.evaluate.w) return;
    uint at = batchWord(pc.evaluate.w + 1u) + LT_BATCH_COMMAND_WORDS * k;
    uvec2 first = batchOrigin(k), next = batchOrigin(k + 1u);
    uint recordIndices = min(next.y, place.words[1]) - min(first.y, place.words[1]);
    place.words[at] = (next.x - first.x + LT_LOCAL_SIZE - 1u) / LT_LOCAL_SIZE;
    place.words[at + 1u] = 1u;
    place.words[at + 2u] = 1u;
    place.words[at + 3u] = (recordIndices + LT_LOCAL_SIZE - 1u) / LT_LOCAL_SIZE;
    place.words[at + 4u] = 1u;
    place.words[at + 5u] = 1u;
    place.words[at + 6u] = next.y - first.y;
    place.words[at + 7u] = 1u;
    place.words[at + 8u] = 0u;
    place.words[at + 9u] = 0u;
    place.words[at + 10u] = 0u;
}

// The record of batch k whose outputs hold frame vertex (component 0) or index (1)
// `g`: a binary search over the batch's records' first outputs in PLACE.
uint recordHolding(uint k, uint g, uint component) {
    uint lo = place.words[batchWord(k)], hi = min(place.words[batchWord(k + 1u)], pc.evaluate.x) - 1u;
    while (lo < hi) {   // the last record starting at or before g
        uint mid = (lo + hi + 1u) / 2u;
        if (place.words[placeWord(mid) + 2u + component] <= g) lo = mid; else hi = mid - 1u;
    }
    return lo;
}

// LT_EVALUATE_BATCH_POINTS: a thread per vertex of batch k = pc.evaluate.z, a
// record's pattern point or an IPP corner (and then its index).
void batchPoint() {
    uint k = pc.evaluate.z;
    uvec2 origin = batchOrigin(k);
    uint g = origin.x + gl_GlobalInvocationID.x;
    if (g >= batchOrigin(k + 1u).x) return;
    uint vertex = g - origin.x;
    if (g >= place.words[0]) {   // an IPP corner: its vertex and its index
        uint corner = g - place.words[0], index = place.words[1] + corner - origin.y;
        evalIppCorner(corner);
        storeVertex(vertex);
        outIndices.i[index] = vertex;
        return;
    }
    uint at = placeWord(recordHolding(k, g, 0u));
    uint record = place.words[at], key = place.words[at + 1u], p = g - place.words[at + 2u];
    uint code = patternHalf(patternTable.words[LT_PT_POINTS] * 2u + patternTable.words[LT_PT_POINT_FIRST + key] + p);
    uint grid = code % LT_PATTERN_GRID_INDICES;
    evalPatternPoint(record, grid % 65u, grid / 65u, 1u << (code / LT_PATTERN_GRID_INDICES));
    storeVertex(vertex);
}

// LT_EVALUATE_BATCH_INDICES: a thread per index of batch k's records.
void batchIndex() {
    uint k = pc.evaluate.z;
    uvec2 origin = batchOrigin(k);
    uint g = origin.y + gl_GlobalInvocationID.x;
    if (g >= min(batchOrigin(k + 1u).y, place.words[1])) return;
    uint at = placeWord(recordHolding(k, g, 1u));
    uint key = place.words[at + 1u], i = g - place.words[at + 3u];
    uint local = LT_PT_LOCAL * 2u + word(commandWord(key, 2u));
    outIndices.i[g - origin.y] = place.words[at + 2u] - origin.x + patternHalf(local + i);
}

// LT_EVALUATE_SORTED_RECORDS: a work group per record (pc.evaluate.z the
// dispatch's first, in record order over the frame's lists): its pattern's points
// and its indices, where PLACE says.
void sortedRecords() {
    uint lid = gl_LocalInvocationID.x, at = placeWord(pc.evaluate.z + gl_WorkGroupID.x);
    uint record = place.words[at], key = place.words[at + 1u];
    uint vertex = place.words[at + 2u], index = place.words[at + 3u];
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
    if (kKind == LT_EVALUATE_BATCHES) {
        batches();
        return;
    }
    if (kKind == LT_EVALUATE_BATCH_ARGS) {
        batchArgs();
        return;
    }
    if (kKind == LT_EVALUATE_BATCH_POINTS) {   // pc.evaluate.z: the batch; pc.level: the IPPs' level
        batchPoint();
        return;
    }
    if (kKind == LT_EVALUATE_BATCH_INDICES) {   // pc.evaluate.z: the batch
        batchIndex();
        return;
    }
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
