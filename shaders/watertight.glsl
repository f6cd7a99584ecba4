// watertight.glsl -- watertight evaluation (runtime/internal/watertight.h: the rules, the
// canonical edge frame and its diagram), operation for operation as
// runtime/src/watertight.cpp and cpu_evaluate.cpp's Evaluator, so both paths round
// alike. Include after common.glsl and box_spline.glsl.
//
// Records (gpu_layout.h): a patch's LT_PATCH_WT words hold, for each corner, the
// index of its point source (patch, edge, x), then the offset of its extras: for
// each edge the index of its root (root edge, offset, scale) or LT_NONE (its own
// edge), for each corner the index of its normal source (patch, corner) or LT_NONE;
// LT_PATCH_WT_BITS holds its static edge bits. Patches are named by global index; x,
// offset and scale are float bits. The watertight pass (watertight_sources.comp)
// evaluates every source and turns every root edge once per frame into the limit
// buffer; patch.tesc gathers those results for its patch, limit.comp for its stencils.

// kEdgeRotation[e][i] of watertight.cpp, flattened.
const int kEdgeRotation[36] = int[36](0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11,
                                      6, 9, 11, 2, 5, 8, 10, 1, 4, 7, 0, 3,
                                      10, 7, 3, 11, 8, 4, 0, 9, 5, 1, 6, 2);
// 1/6 as the CPU's 1.0f / 6.0f.
#define LT_ONE_SIXTH uintBitsToFloat(0x3e2aaaabu)

uint patchWordsOf(uint patchIndex) { return word(LT_H_PATCHES) + LT_PATCH_WORDS * patchIndex; }

// The 12 points of the patch at `patchWords`, phantoms filled.
void loadPatchPoints(uint patchWords, out vec3 p[12]) {
    for (int i = 0; i < 12; ++i) p[i] = vertexAt(word(patchWords + uint(i)));
    fillPhantomPoints(word(patchWords + LT_PATCH_INFO) & 0x3fu, p);
}

bool edgeFlipped(uint patchWords, int edge) {
    return word(patchWords + uint(kEdgeRotation[12 * edge + 4])) > word(patchWords + uint(kEdgeRotation[12 * edge + 5]));
}

float edgeLocalParameter(int edge, float s, float t) {
    precise float back = 1.0 - t;
    return edge == 0 ? s : edge == 1 ? t : back;
}

// The cubic B-spline of canonical-edge points 3 4 5 6 at x (boundary and
// infinitely sharp edges).
vec3 edgeCubic(vec3 q[12], float x) {
    precise float y = 1.0 - x;
    precise float x2 = x * x;
    precise float x3 = x2 * x;
    precise float c0 = (y * y * y) * LT_ONE_SIXTH;
    precise float c2 = (((3.0 * x2 - 3.0 * x3) + 3.0 * x) + 1.0) * LT_ONE_SIXTH;
    precise float c3 = x3 * LT_ONE_SIXTH;
    precise vec3 e = c0 * (q[3] - q[4]);
    e = e + c2 * (q[5] - q[4]);
    e = e + c3 * (q[6] - q[4]);
    precise vec3 line = q[4] + e;
    return line;
}

// e[i] = q[kEdgeRotation[edge][flip ? 9 - i : i]], i < 10, by selects between constant
// indices: lavapipe gathers a dynamically indexed local array lane by lane.
void rotateToEdge(vec3 q[12], int edge, bool flip, inout vec3 e[12]) {
    for (int i = 0; i < 10; ++i) {
        vec3 e0 = flip ? q[kEdgeRotation[9 - i]] : q[kEdgeRotation[i]];
        vec3 e1 = flip ? q[kEdgeRotation[21 - i]] : q[kEdgeRotation[12 + i]];
        vec3 e2 = flip ? q[kEdgeRotation[33 - i]] : q[kEdgeRotation[24 + i]];
        e[i] = edge == 0 ? e0 : edge == 1 ? e1 : e2;
    }
}

// evalCanonicalEdge of watertight.cpp.
void evalCanonicalEdge(vec3 p[12], uint patchWords, int edge, float x, out vec3 pos, out vec3 ds, out vec3 dt) {
    vec3 q[12];
    rotateToEdge(p, edge, edgeFlipped(patchWords, edge), q);
    q[10] = q[4];
    q[11] = q[4];
    float w[12], ws[12], wt[12];
    boxSplineEdgeWeights(x, w, ws, wt);
    vec3 position;
    sumWeighted(q, 10, w, ws, wt, position, ds, dt);  // points 10 and 11 weigh 0 on the edge
    // Boundary or infinitely sharp edge: the cubic B-spline of points 3 4 5 6.
    if ((word(patchWords + LT_PATCH_INFO) & (1u << uint(edge))) != 0u) position = edgeCubic(q, x);
    pos = position;
}

// Evaluator::evalSource: edge `edge` of patch `patchIndex` at x; n = ds x dt.
void evalSource(uint patchIndex, int edge, float x, out vec3 pos, out vec3 n) {
    uint patchWords = patchWordsOf(patchIndex);
    vec3 q[12];
    loadPatchPoints(patchWords, q);
    vec3 ds, dt;
    evalCanonicalEdge(q, patchWords, edge, x, pos, ds, dt);
    n = crossProduct(ds, dt);
}

// Evaluator::evalNormalSource (rule 4): the box-spline normal of a patch at its corner.
vec3 evalNormalSource(uint record) {
    vec3 q[12];
    loadPatchPoints(patchWordsOf(word(record)), q);
    uint c = word(record + 1u);
    vec3 pos, du, dv;
    evalBoxSpline(q, c == 1u ? 1.0 : 0.0, c == 2u ? 1.0 : 0.0, pos, du, dv);
    return crossProduct(du, dv);
}

void evalPointSource(uint record, out vec3 pos, out vec3 n) {
    evalSource(word(record), int(word(record + 1u)), wordFloat(record + 2u), pos, n);
}

vec3 limitVec3(uint at) { return vec3(limit.v[at], limit.v[at + 1u], limit.v[at + 2u]); }

// The watertight patch interface: patch.tesc reads the tables once per patch and
// hands patch.tese what its points need, so the evaluation shader, which runs per
// domain point, reads storage only at corners (lavapipe gathers storage reads lane
// by lane, and its control shader pays for every output it stores: the interface
// carries as little as it can).
//
//   per output vertex v (0..3; patch.tesc: vertex v carries points 3v .. 3v + 2):
//     wtEdge[v][3K + m]  for a rooted edge K, canonical point 3v + m < 10 of its root
//                        edge (the roots pass); not written for other edges:
//                        patch.tese turns this patch's own points by selects
//   per patch:
//     wtCornerAt[c]   (a, b): corner c's point source results are limit[a ..]
//                     (position) and limit[a + 3 ..] (n, rule 5's direction); b: its
//                     sector's normal (rule 4) at limit[b ..], or LT_NONE (then n)
//     wtEdgeMap[K]    (offset, scale): x_c = offset + scale * x onto edge K's source
//                     edge ((0, 1) for its own edge: exact)
//     wtEdgeBits      the patch's LT_PATCH_WT_BITS (gpu_layout.h)
//
// LT_WT_VERT (pattern.vert, evaluate.comp: no tessellation stages) keeps the same
// interface as private variables of one invocation, which gathers what its own point
// reads (prepareWatertightPoint) and then runs what patch.tese runs.
#if defined(LT_WT_TESC) || defined(LT_WT_TESE)
#ifdef LT_WT_TESC
#define LT_WT_IO out
#else
#define LT_WT_IO in
#endif
layout(location = 3) LT_WT_IO vec3 wtEdge[][9];
layout(location = 16) patch LT_WT_IO uvec2 wtCornerAt[3];
layout(location = 19) patch LT_WT_IO vec2 wtEdgeMap[3];
layout(location = 22) patch LT_WT_IO uint wtEdgeBits;
#endif
#ifdef LT_WT_VERT
vec3 wtEdge[4][9];
uvec2 wtCornerAt[3];
vec2 wtEdgeMap[3];
uint wtEdgeBits;
#endif

#ifdef LT_WT_TESC
// patch.tesc, invocation v: canonical points 3v .. 3v + 2 of each rooted edge, then
// the per-patch outputs of corner and edge v (v < 3; invocation 3 repeats 2, the same
// values: lavapipe runs the four as lanes of one batch, and a branch on v that left
// lane 3 out measured slower than the repeated reads).
void prepareWatertight(uint patchWords) {
    uint v = uint(gl_InvocationID);
    uint bits = word(patchWords + LT_PATCH_WT_BITS);
    uint extra = word(patchWords + LT_PATCH_WT + 3u);
    uint rootRecords = word(LT_H_WT_ROOTS), rootResults = word(LT_H_WT_ROOT_RESULTS);
    for (int e = 0; e < 3; ++e) {
        if ((bits & (LT_WT_BIT_ROOT << uint(e))) == 0u) continue;  // patch.tese turns p itself
        uint record = rootRecords + LT_WT_ROOT_WORDS * word(extra + uint(e));
        uint roots = rootResults + LT_WT_ROOT_FLOATS * word(record);
        for (int m = 0; m < 3; ++m) {
            uint i = 3u * v + uint(m);
            if (i < 10u) wtEdge[gl_InvocationID][3 * e + m] = limitVec3(roots + 3u * i);  // 10, 11: unused
        }
    }
    uint c = min(v, 2u);
    uint at = word(LT_H_WT_POINT_RESULTS) + LT_WT_POINT_FLOATS * word(patchWords + LT_PATCH_WT + c);
    uint sector = extra != LT_NONE ? word(extra + 3u + c) : LT_NONE;
    if (sector != LT_NONE) sector = word(LT_H_WT_NORMAL_RESULTS) + LT_WT_NORMAL_FLOATS * sector;
    vec2 map = vec2(0.0, 1.0);
    if ((bits & (LT_WT_BIT_ROOT << c)) != 0u) {
        uint record = word(LT_H_WT_ROOTS) + LT_WT_ROOT_WORDS * word(extra + c);
        map = vec2(wordFloat(record + 1u), wordFloat(record + 2u));
    }
    wtCornerAt[c] = uvec2(at, sector);
    wtEdgeMap[c] = map;
    wtEdgeBits = bits;
}
#endif

#ifdef LT_WT_VERT
// pattern.vert and evaluate.comp: what prepareWatertight's four invocations gather,
// but only what domain point (s, t) reads: the root of its edge (edge 0 inside the
// patch, unused there) and the source of its corner (corner 0 elsewhere, unused).
// A quarter of the reads of all four slots.
void prepareWatertightPoint(uint patchWords, float s, float t) {
    int corner = s == 0.0 ? (t == 0.0 ? 0 : t == 1.0 ? 2 : -1) : (s == 1.0 && t == 0.0 ? 1 : -1);
    precise float sum = s + t;
    int edge = t == 0.0 ? 0 : sum == 1.0 ? 1 : s == 0.0 ? 2 : -1;
    uint k = uint(max(edge, 0)), c = uint(max(corner, 0));
    uint bits = word(patchWords + LT_PATCH_WT_BITS);
    uint extra = word(patchWords + LT_PATCH_WT + 3u);
    wtEdgeBits = bits;
    vec2 map = vec2(0.0, 1.0);
    if ((bits & (LT_WT_BIT_ROOT << k)) != 0u) {
        uint record = word(LT_H_WT_ROOTS) + LT_WT_ROOT_WORDS * word(extra + k);
        uint roots = word(LT_H_WT_ROOT_RESULTS) + LT_WT_ROOT_FLOATS * word(record);
        for (int i = 0; i < 10; ++i) {
            vec3 q = limitVec3(roots + 3u * uint(i));
            if (k == 0u) wtEdge[i / 3][i % 3] = q;
            else if (k == 1u) wtEdge[i / 3][3 + i % 3] = q;
            else wtEdge[i / 3][6 + i % 3] = q;
        }
        map = vec2(wordFloat(record + 1u), wordFloat(record + 2u));
    }
    if (k == 0u) wtEdgeMap[0] = map;
    else if (k == 1u) wtEdgeMap[1] = map;
    else wtEdgeMap[2] = map;
    uint at = word(LT_H_WT_POINT_RESULTS) + LT_WT_POINT_FLOATS * word(patchWords + LT_PATCH_WT + c);
    uint sector = extra != LT_NONE ? word(extra + 3u + c) : LT_NONE;
    if (sector != LT_NONE) sector = word(LT_H_WT_NORMAL_RESULTS) + LT_WT_NORMAL_FLOATS * sector;
    if (c == 0u) wtCornerAt[0] = uvec2(at, sector);
    else if (c == 1u) wtCornerAt[1] = uvec2(at, sector);
    else wtCornerAt[2] = uvec2(at, sector);
}
#endif

#if defined(LT_WT_TESE) || defined(LT_WT_VERT)
// The canonical points of edge k (0..2): the root's from patch.tesc's outputs, else
// this patch's p turned (rotateToEdge); points 10 and 11 repeat point 4.
void canonicalPoints(vec3 p[12], uint k, uint bits, out vec3 f[12]) {
    rotateToEdge(p, int(k), (bits & (LT_WT_BIT_FLIP << k)) != 0u, f);
    bool rooted = (bits & (LT_WT_BIT_ROOT << k)) != 0u;
    for (int i = 0; i < 10; ++i) {
        vec3 root = k == 0u ? wtEdge[i / 3][i % 3] : k == 1u ? wtEdge[i / 3][3 + i % 3] : wtEdge[i / 3][6 + i % 3];
        f[i] = rooted ? root : f[i];
    }
    f[10] = f[4];
    f[11] = f[4];
}

// Evaluator::evalWatertight: domain point (s,t) of this patch, whose points (phantoms
// filled) are p. n (shading) and dir (displacement, rule 5) are not unit.
//
// lavapipe runs a batch of 8 points of one patch in lock step, and code under a
// branch some of its lanes take runs for all of them with stores masked, which cost
// this function a third of the evaluation shader's time. So every point runs the same
// straight line: one box-spline evaluation (two on sharp edges with kSpecDisplace,
// see 2.) on points picked by selects (lavapipe indexes a local array lane by lane),
// then selects between the cases. Only the corners' reads of the watertight pass's
// results are behind a branch (storage reads are gathered lane by lane); it writes
// three vectors. A canonical edge is the box spline of its rotated points at (x, 0)
// with points 10 and 11 set to point 4: their terms are exactly 0 there, so the sums
// round as evalCanonicalEdge's 10-point sums.
void evalWatertight(vec3 p[12], float s, float t, out vec3 pos, out vec3 n, out vec3 dir) {
    int corner = s == 0.0 ? (t == 0.0 ? 0 : t == 1.0 ? 2 : -1) : (s == 1.0 && t == 0.0 ? 1 : -1);
    precise float sum = s + t;
    int edge = t == 0.0 ? 0 : sum == 1.0 ? 1 : s == 0.0 ? 2 : -1;
    bool onEdge = edge >= 0;
    // 1. Where the position comes from: the interior of this patch, or edge `edge`'s
    //    source at x.
    uint k = uint(max(edge, 0));
    uint bits = wtEdgeBits;
    float local = edgeLocalParameter(int(k), s, t);
    precise float flipped = 1.0 - local;
    float own = (bits & (LT_WT_BIT_FLIP << k)) != 0u ? flipped : local;
    vec2 map = k == 0u ? wtEdgeMap[0] : k == 1u ? wtEdgeMap[1] : wtEdgeMap[2];
    precise float x = map.x + map.y * own;
    // 2. Rule 4 on a boundary or sharp edge: this side's own box-spline normal; the
    //    position is then edgeCubic's. Rule 5's direction (displacement) needs the
    //    canonical evaluation too; without it one evaluation does: this patch's on such
    //    an edge, else the canonical one. That needs the edge's source to be a crease
    //    edge as well: gpu_tables.cpp checks it, else pipelines keep kSpecDisplace.
    bool crease = onEdge && (bits & (LT_WT_BIT_CREASE << k)) != 0u;
    bool sharp = onEdge && (bits & (LT_WT_BIT_SHARP << k)) != 0u;
    bool canonical = kSpecDisplace ? onEdge : onEdge && !sharp;
    vec3 c[12], f[12];
    canonicalPoints(p, k, bits, c);
    for (int i = 0; i < 12; ++i) f[i] = canonical ? c[i] : p[i];
    vec3 ds, dt;
    evalBoxSpline(f, canonical ? x : s, canonical ? 0.0 : t, pos, ds, dt);
    n = crossProduct(ds, dt);
    dir = n;  // rule 5 (unused without kSpecDisplace)
    if (kSpecDisplace && sharp) {
        vec3 ownPos;
        evalBoxSpline(p, s, t, ownPos, ds, dt);
        n = crossProduct(ds, dt);
    }
    vec3 cubic = edgeCubic(c, x);
    pos = crease ? cubic : pos;
    // 3. A corner: its source's position and normal; rule 4, its sector's normal.
    vec3 cornerPos = vec3(0.0), cornerDir = vec3(0.0), cornerN = vec3(0.0);
    if (corner >= 0) {  // skipped by batches without a corner
        uvec2 at = corner == 0 ? wtCornerAt[0] : corner == 1 ? wtCornerAt[1] : wtCornerAt[2];
        cornerPos = limitVec3(at.x);
        cornerDir = limitVec3(at.x + 3u);
        cornerN = at.y != LT_NONE ? limitVec3(at.y) : cornerDir;
    }
    pos = corner >= 0 ? cornerPos : pos;
    dir = corner >= 0 ? cornerDir : dir;
    n = corner >= 0 ? cornerN : n;
}
#endif
