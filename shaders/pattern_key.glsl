// pattern_key.glsl -- the refinement pattern of a draw record at screen-space factors
// (patterns.h): pattern_sort.comp sorts the records by it, evaluate.comp writes each
// record's pattern. Include after common.glsl and record_factors.glsl.
#ifndef LT_PATTERN_KEY_GLSL
#define LT_PATTERN_KEY_GLSL

// patterns.h's patternFactor, as its exponent: f rounded up to 2^k, k in [0, 6]
// (NaN and f <= 1: 0).
uint patternExponent(float f) {
    uint k = 0u;
    precise float e = 1.0;
    while (k < 6u && e < f) {
        e *= 2.0;
        ++k;
    }
    return k;
}

// The pattern key (gpu_layout.h) of `record`'s edge factors.
uint recordKey(uint record) {
    uint patchWords = word(LT_H_PATCHES) + LT_PATCH_WORDS * (record & LT_RECORD_PATCH_MASK);
    vec3 corner[3] = vec3[3](vertexAt(word(patchWords + 4u)), vertexAt(word(patchWords + 5u)),
                             vertexAt(word(patchWords + 8u)));
    vec3 o = recordOuterFactors(record, patchWords, word(patchWords + LT_PATCH_INFO), corner);
    return patternExponent(o.x) * 49u + patternExponent(o.y) * 7u + patternExponent(o.z);
}

#endif
