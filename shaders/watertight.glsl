// watertight.glsl -- watertight evaluation (runtime/src/watertight.h: the rules, the
// canonical edge frame and its diagram), operation for operation as
// runtime/src/watertight.cpp and cpu_evaluate.cpp's Evaluator, so both paths round
// alike. Include after common.glsl and box_spline.glsl.
//
// Records (gpu_layout.h): a patch's LT_PATCH_WT words hold, for each corner, the
// index of its point source (patch, edge, x), then the offset of its extras: for
// each edge its root (patch, edge, offset, scale) or LT_NONE (its own edge), for
// each corner the index of its normal source (patch, corner) or LT_NONE. Patches are
// named by global index; x, offset and scale are float bits. The watertight pass
// (watertight_sources.comp) evaluates every source once per frame into the limit
// buffer; the draws read those results (LT_WRITE_LIMIT: not in a writing shader).

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

// evalCanonicalEdge of watertight.cpp.
void evalCanonicalEdge(vec3 p[12], uint patchWords, int edge, float x, out vec3 pos, out vec3 ds, out vec3 dt) {
    bool flip = edgeFlipped(patchWords, edge);
    vec3 q[12];
    for (int i = 0; i < 10; ++i) q[i] = p[kEdgeRotation[12 * edge + (flip ? 9 - i : i)]];
    q[10] = q[4];
    q[11] = q[4];
    float w[12], ws[12], wt[12];
    boxSplineWeights(x, 0.0, w, ws, wt);
    vec3 position;
    sumWeighted(q, 10, w, ws, wt, position, ds, dt);  // points 10 and 11 weigh 0 on the edge
    // Boundary or infinitely sharp edge: the cubic B-spline of points 3 4 5 6.
    if ((word(patchWords + LT_PATCH_INFO) & (1u << uint(edge))) != 0u) position = edgeCubic(q, x);
    pos = position;
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

#ifndef LT_WRITE_LIMIT
vec3 limitVec3(uint at) { return vec3(limit.v[at], limit.v[at + 1u], limit.v[at + 2u]); }

// Evaluator::evalWatertight: domain point (s,t) of the patch at `patchWords`, whose
// points (phantoms filled) are p. n (shading) and dir (displacement, rule 5) are not unit.
//
// A corner reads the watertight pass's evaluation of its sources (evalPointSource,
// evalNormalSource: the bits the CPU's evaluation has). Other points: one box-spline
// evaluation whatever the case (two with kSpecDisplace, see 2.): lavapipe runs both
// sides of every branch (masked), so each evaluation written out costs every
// invocation, corners included. A canonical edge is the box spline of its
// rotated points at (x, 0) with points 10 and 11 set to point 4: their terms are
// exactly 0 there, so the sums round as evalCanonicalEdge's 10-point sums.
void evalWatertight(uint patchWords, vec3 p[12], float s, float t, out vec3 pos, out vec3 n, out vec3 dir) {
    uint mask = word(patchWords + LT_PATCH_INFO) & 0x3fu;
    int corner = s == 0.0 ? (t == 0.0 ? 0 : t == 1.0 ? 2 : -1) : (s == 1.0 && t == 0.0 ? 1 : -1);
    precise float sum = s + t;
    int edge = t == 0.0 ? 0 : sum == 1.0 ? 1 : s == 0.0 ? 2 : -1;
    uint extra = word(patchWords + LT_PATCH_WT + 3u);
    // 1. Where the position comes from: a patch's points, an edge of it (-1: the
    //    interior of this patch) and the parameter along it.
    uint srcWords = patchWords;
    int srcEdge = -1;
    float x = 0.0;
    bool load = false;
    if (corner < 0 && edge >= 0) {
        float local = edgeLocalParameter(edge, s, t);
        precise float flipped = 1.0 - local;
        x = edgeFlipped(patchWords, edge) ? flipped : local;
        srcEdge = edge;
        uint root = extra == LT_NONE ? LT_NONE : word(extra + uint(edge));
        if (root != LT_NONE) {
            precise float xc = wordFloat(root + 2u) + wordFloat(root + 3u) * x;
            x = xc;
            srcWords = patchWordsOf(word(root));
            srcEdge = int(word(root + 1u));
            load = true;
        }
    }
    vec3 q[12];
    if (load) loadPatchPoints(srcWords, q); else q = p;
    vec3 e[12];
    float es = s, et = t;
    if (srcEdge >= 0) {  // evalCanonicalEdge's frame
        bool flip = edgeFlipped(srcWords, srcEdge);
        rotateToEdge(q, srcEdge, flip, e);
        e[10] = e[4];
        e[11] = e[4];
        es = x;
        et = 0.0;
    } else {
        e = q;
    }
    // 2. Rule 4 on a boundary or sharp edge: this side's own box-spline normal; the
    //    position is then edgeCubic's. Rule 5's direction (displacement) needs the
    //    canonical evaluation too; without it one evaluation does: this patch's on such
    //    an edge, else the canonical one. That needs the edge's source to be a crease
    //    edge as well: gpu_tables.cpp checks it, else pipelines keep kSpecDisplace.
    bool crease = srcEdge >= 0 && (word(srcWords + LT_PATCH_INFO) & (1u << uint(srcEdge))) != 0u;
    bool own = srcEdge >= 0 && (mask & (1u << uint(edge))) != 0u;
    vec3 ds, dt;
    if (kSpecDisplace) {
        evalBoxSpline(e, es, et, pos, ds, dt);
        n = crossProduct(ds, dt);
        dir = n;  // rule 5
        if (own) {
            vec3 ownPos;
            evalBoxSpline(p, s, t, ownPos, ds, dt);
            n = crossProduct(ds, dt);
        }
    } else {
        vec3 f[12];
        if (own) f = p; else f = e;
        evalBoxSpline(f, own ? s : es, own ? t : et, pos, ds, dt);
        n = crossProduct(ds, dt);
        dir = n;  // unused: no displacement
    }
    if (crease) pos = edgeCubic(e, x);
    // 3. A corner: its source's position and normal (the watertight pass's); rule 4,
    //    its sector's normal.
    if (corner >= 0) {
        uint at = word(LT_H_WT_POINT_RESULTS) + LT_WT_POINT_FLOATS * word(patchWords + LT_PATCH_WT + uint(corner));
        pos = limitVec3(at);
        n = limitVec3(at + 3u);
        dir = n;
        uint sector = extra == LT_NONE ? LT_NONE : word(extra + 3u + uint(corner));
        if (sector != LT_NONE) n = limitVec3(word(LT_H_WT_NORMAL_RESULTS) + LT_WT_NORMAL_FLOATS * sector);
    }
}
#endif
