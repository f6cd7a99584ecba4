// Private to the runtime: the weights of Loop's rules, shared by the CPU path and
// the tables uploaded to the GPU, so both compute with the same floats.
#pragma once

#include <cstdint>

namespace lt {

// Smooth vertex rule of valence n: v' = vertex * v + edge * sum(ring).
struct SmoothWeights {
    float vertex = 0, edge = 0;
};
SmoothWeights loopSmoothWeights(uint32_t valence);

// Edge rule with crease weight w: e = ends * (a + b) + opposite * (c + d).
struct EdgeWeights {
    float ends, opposite;
};
inline EdgeWeights edgeWeights(float w) {
    if (w == 0.0f) return {0.375f, 0.125f};
    return {(1.0f - w) * 0.375f + w * 0.5f, (1.0f - w) * 0.125f};
}

} // namespace lt
