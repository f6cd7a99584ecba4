// Private to the runtime: the weights of Loop's rules, shared by the CPU path and
// the tables uploaded to the GPU, so both compute with the same floats.
#pragma once

#include <cstdint>
#include <vector>

namespace lt {

// Smooth vertex rule of valence n: v' = vertex * v + edge * sum(ring).
struct SmoothWeights {
    float vertex = 0, edge = 0;
};
SmoothWeights loopSmoothWeights(uint32_t valence);

// Loop's smooth limit masks for a closed ring of n neighbours: the same position
// weight for every neighbour, tangent weights cos and sin of 2 pi k / n.
struct SmoothLimitWeights {
    float position = 0;
    std::vector<float> tangentU, tangentV;
};
SmoothLimitWeights loopSmoothLimitWeights(uint32_t valence);

// Edge rule with crease weight w: e = ends * (a + b) + opposite * (c + d).
struct EdgeWeights {
    float ends, opposite;
};
inline EdgeWeights edgeWeights(float w) {
    if (w == 0.0f) return {0.375f, 0.125f};
    return {(1.0f - w) * 0.375f + w * 0.5f, (1.0f - w) * 0.125f};
}

}  // namespace lt
