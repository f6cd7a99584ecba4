// displacement.glsl -- the displacement map of the asset (spec "Displacement map"),
// sampled bit for bit as runtime/src/displacement.cpp does: the same operations in
// the same order, every one `precise` (no fusing, no reassociation). Change both
// together.
//
// Include after common.glsl. The map lives in the tables buffer (binding
// LT_BINDING_TABLES) at word(LT_H_DISPLACEMENT), laid out as gpu_layout.h's LT_D_*
// (filled by runtime/src/vulkan/gpu_tables.cpp):
//
//   bool  hasDisplacement()
//   float sampleDisplacement(uint baseFace, float u, float v)
//         scale * value + bias at (u, v) on the base face (corners (0,0), (1,0),
//         (0,1)); 0.0 without a map. Identical bits from every face on a shared
//         base edge (exactly v == 0, u == 0 or u + v == 1) and at a shared corner;
//         see displacement.h for the rules.
//
//   displaced = position + unitNormal * sampleDisplacement(face, u, v)

// 1/65535 rounded to float (bits 0x37800080): the unorm16 decode, as kUnorm16.
#define LT_UNORM16 uintBitsToFloat(0x37800080u)

bool hasDisplacement() { return word(LT_H_DISPLACEMENT) != LT_NONE; }

uint ltDispField(uint field) { return word(word(LT_H_DISPLACEMENT) + field); }

// Sample k (0 .. 65535) as a float (exact).
float ltDispQ(uint k) {
    uint w = word(ltDispField(LT_D_SAMPLES) + (k >> 1u));
    return float((w >> (16u * (k & 1u))) & 0xffffu);
}

// Index of grid point (i, j) of face `face`'s tile (asset.h's displacementSample).
uint ltDispSample(uint face, uint i, uint j) {
    uint R = ltDispField(LT_D_RESOLUTION);
    uint fw = ltDispField(LT_D_FACES) + LT_D_FACE_WORDS * face;
    uint k;      // face edge
    uint p;      // sample 1 .. R-1 along it, counted from its corner k
    if (j == 0u) {
        if (i == 0u) return word(fw);
        if (i == R) return word(fw + 1u);
        k = 0u;
        p = i;
    } else if (i + j == R) {
        if (j == R) return word(fw + 2u);
        k = 1u;
        p = j;
    } else if (i == 0u) {
        k = 2u;
        p = R - j;
    } else {
        uint interior = (R - 1u) * (R - 2u) / 2u;
        uint row = (j - 1u) * (R - 1u) - (j - 1u) * j / 2u;
        return ltDispField(LT_D_VERTICES) + face * interior + row + (i - 1u);
    }
    uint from = word(fw + k), to = word(fw + (k + 1u) % 3u);
    uint edge = word(fw + 3u + k);
    return ltDispField(LT_D_EDGE_BASE) + edge * (R - 1u) + (from < to ? p : R - p) - 1u;
}

// edgeQ of displacement.cpp: q at parameter t from `lo` along edge `edge`.
float ltDispEdgeQ(uint lo, uint hi, uint edge, float t) {
    uint R = ltDispField(LT_D_RESOLUTION);
    uint first = ltDispField(LT_D_EDGE_BASE) + edge * (R - 1u);
    precise float x = t * float(R);
    uint k = min(uint(x), R - 1u);
    precise float f = x - float(k);
    float q0 = k == 0u ? ltDispQ(lo) : ltDispQ(first + k - 1u);
    float q1 = k + 1u == R ? ltDispQ(hi) : ltDispQ(first + k);
    precise float q = q0 + f * (q1 - q0);
    return q;
}

// interiorQ of displacement.cpp.
float ltDispInteriorQ(uint face, float u, float v) {
    float R = float(ltDispField(LT_D_RESOLUTION));
    precise float x = u * R;
    precise float y = v * R;
    uint i = uint(x), j = uint(y);
    precise float fx = x - float(i);
    precise float fy = y - float(j);
    precise float sum = fx + fy;
    float q0, q1, q2;
    precise float w0, w1, w2;
    if (sum > 1.0) {
        q0 = ltDispQ(ltDispSample(face, i + 1u, j + 1u));
        q1 = ltDispQ(ltDispSample(face, i, j + 1u));
        q2 = ltDispQ(ltDispSample(face, i + 1u, j));
        w0 = sum - 1.0;
        w1 = 1.0 - fx;
        w2 = 1.0 - fy;
    } else {
        q0 = ltDispQ(ltDispSample(face, i, j));
        q1 = ltDispQ(ltDispSample(face, i + 1u, j));
        q2 = ltDispQ(ltDispSample(face, i, j + 1u));
        w0 = (1.0 - fx) - fy;
        w1 = fx;
        w2 = fy;
    }
    precise float q = (w0 * q0 + w1 * q1) + w2 * q2;
    return q;
}

float sampleDisplacement(uint baseFace, float u, float v) {
    if (!hasDisplacement()) return 0.0;
    u = u > 0.0 ? min(u, 1.0) : 0.0;   // NaN and negatives to 0 (as clamp01)
    v = v > 0.0 ? min(v, 1.0) : 0.0;
    uint fw = ltDispField(LT_D_FACES) + LT_D_FACE_WORDS * baseFace;
    uint c0 = word(fw), c1 = word(fw + 1u), c2 = word(fw + 2u);
    precise float q;
    precise float uv = u + v;
    if (v == 0.0) {          // edge 0, c0 -> c1: u measures from c0
        q = c0 < c1 ? ltDispEdgeQ(c0, c1, word(fw + 3u), u) : ltDispEdgeQ(c1, c0, word(fw + 3u), 1.0 - u);
    } else if (u == 0.0) {   // edge 2, c2 -> c0: v measures from c0
        q = c0 < c2 ? ltDispEdgeQ(c0, c2, word(fw + 5u), v) : ltDispEdgeQ(c2, c0, word(fw + 5u), 1.0 - v);
    } else if (uv >= 1.0) {  // edge 1, c1 -> c2: v measures from c1, u from c2
        q = c1 < c2 ? ltDispEdgeQ(c1, c2, word(fw + 4u), v) : ltDispEdgeQ(c2, c1, word(fw + 4u), u);
    } else {
        q = ltDispInteriorQ(baseFace, u, v);
    }
    float scale = uintBitsToFloat(ltDispField(LT_D_SCALE)), bias = uintBitsToFloat(ltDispField(LT_D_BIAS));
    precise float d = scale * (q * LT_UNORM16) + bias;
    return d;
}
