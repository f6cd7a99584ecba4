// runtime/src/face_attributes.h -- private to looptess_runtime: the one definition of
// runtime.h's surface attribute arithmetic (faceAttribute, faceTexcoord,
// faceTangent), inline so the CPU evaluator's per-vertex loop keeps it inlined. The
// public functions (face_attributes.cpp) call these. Compiled only in the library's
// sources, with -ffp-contract=off (looptess_flags): never include it elsewhere, or
// another translation unit's flags could give other bits.
#pragma once

#include <cmath>
#include <limits>

namespace lt::detail {

// The unit vector of `a` (the file's "Unit normals"), as shaders/common.glsl's
// unitNormal, operation for operation:
//   1. |a|^2 a normal float (no under- or overflow): a / |a|;
//   2. else, every component finite and the largest magnitude m >= FLT_MIN: the
//      same of a / m (its largest component is exactly +-1, so |a / m|^2 is in
//      [1, 3] and neither under- nor overflows);
//   3. else (a zero, subnormal, infinite or NaN): (0, 0, 1).
// Never zero, never non-finite. A function of `a`'s bits alone, so a point whose
// vector every primitive computes alike gets the same unit vector from each.
inline void unitVector(const float a[3], float out[3]) {
    constexpr float kMin = std::numeric_limits<float>::min(), kMax = std::numeric_limits<float>::max();
    const float squared = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
    if (squared >= kMin && squared <= kMax) {
        const float len = std::sqrt(squared);
        for (int k = 0; k < 3; ++k) out[k] = a[k] / len;
        return;
    }
    float m = 0.0f;
    bool finite = true;
    for (int k = 0; k < 3; ++k) {
        const float magnitude = std::fabs(a[k]);
        finite = finite && magnitude <= kMax;  // false for NaN too
        m = magnitude > m ? magnitude : m;
    }
    if (!finite || m < kMin) {
        out[0] = out[1] = 0.0f;
        out[2] = 1.0f;
        return;
    }
    const float b[3] = {a[0] / m, a[1] / m, a[2] / m};
    const float len = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    for (int k = 0; k < 3; ++k) out[k] = b[k] / len;
}

inline void faceAttribute(const float* c, int width, float u, float v, float* out) {
    const float w = 1.0f - u - v;
    for (int k = 0; k < width; ++k) out[k] = w * c[k] + u * c[width + k] + v * c[2 * width + k];
}

inline void faceTexcoord(const float c[6], float u, float v, float st[2]) { faceAttribute(c, 2, u, v, st); }

inline void faceTangent(const float c[6], const float pu[3], const float pv[3], const float n[3], float out[4]) {
    const float s1 = c[2] - c[0], t1 = c[3] - c[1], s2 = c[4] - c[0], t2 = c[5] - c[1];
    const float det = s1 * t2 - s2 * t1;
    float w = det < 0.0f ? -1.0f : 1.0f;
    float g[3];
    for (int k = 0; k < 3; ++k) g[k] = (t2 * pu[k] - t1 * pv[k]) * w;
    if (g[0] == 0.0f && g[1] == 0.0f && g[2] == 0.0f) {
        for (int k = 0; k < 3; ++k) g[k] = pu[k];
        w = 1.0f;
    }
    const float along = n[0] * g[0] + n[1] * g[1] + n[2] * g[2];
    for (int k = 0; k < 3; ++k) g[k] = g[k] - n[k] * along;
    unitVector(g, out);
    out[3] = w;
}

}  // namespace lt::detail
