// watertight.glsl -- watertight evaluation (runtime/src/watertight.h: the rules, the
// canonical edge frame and its diagram), operation for operation as
// runtime/src/watertight.cpp and cpu_evaluate.cpp's Evaluator, so both paths round
// alike. Include after common.glsl and box_spline.glsl.
//
// Records (gpu_layout.h): a patch's LT_PATCH_WT words hold, for each corner, the
// offset of its point source (patch, edge, x), then the offset of its extras: for
// each edge its root (patch, edge, offset, scale) or LT_NONE (its own edge), for
// each corner its normal source (patch, corner) or LT_NONE. Patches are named by
// global index; x, offset and scale are float bits.

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
    if ((word(patchWords + LT_PATCH_INFO) & (1u << uint(edge))) != 0u) {
        // Boundary or infinitely sharp edge: the cubic B-spline of points 3 4 5 6.
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
        position = line;
    }
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

// Evaluator::evalWatertight: domain point (s,t) of the patch at `patchWords`, whose
// points (phantoms filled) are p. n (shading) and dir (displacement, rule 5) are not unit.
void evalWatertight(uint patchWords, vec3 p[12], float s, float t, out vec3 pos, out vec3 n, out vec3 dir) {
    uint mask = word(patchWords + LT_PATCH_INFO) & 0x3fu;
    vec3 ds, dt;
    int corner = s == 0.0 ? (t == 0.0 ? 0 : t == 1.0 ? 2 : -1) : (s == 1.0 && t == 0.0 ? 1 : -1);
    precise float sum = s + t;
    int edge = t == 0.0 ? 0 : sum == 1.0 ? 1 : s == 0.0 ? 2 : -1;
    uint extra = word(patchWords + LT_PATCH_WT + 3u);
    if (corner >= 0) {
        evalPointSource(word(patchWords + LT_PATCH_WT + uint(corner)), pos, n);
        dir = n;  // rule 5
        uint sector = extra == LT_NONE ? LT_NONE : word(extra + 3u + uint(corner));
        if (sector != LT_NONE) n = evalNormalSource(sector);  // rule 4
        return;
    }
    if (edge < 0) {
        evalBoxSpline(p, s, t, pos, ds, dt);
        n = crossProduct(ds, dt);
        dir = n;
    } else {
        float local = edgeLocalParameter(edge, s, t);
        precise float flipped = 1.0 - local;
        float x = edgeFlipped(patchWords, edge) ? flipped : local;
        uint root = extra == LT_NONE ? LT_NONE : word(extra + uint(edge));
        if (root != LT_NONE) {
            precise float xc = wordFloat(root + 2u) + wordFloat(root + 3u) * x;
            evalSource(word(root), int(word(root + 1u)), xc, pos, n);
        } else {
            evalCanonicalEdge(p, patchWords, edge, x, pos, ds, dt);
            n = crossProduct(ds, dt);
        }
        dir = n;  // rule 5
        if ((mask & (1u << uint(edge))) != 0u) {  // rule 4: the position is shared, the normal this side's
            vec3 own;
            evalBoxSpline(p, s, t, own, ds, dt);
            n = crossProduct(ds, dt);
        }
    }
}
