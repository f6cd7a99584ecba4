// tests/runtime/contraction_calls.h -- what test_contraction.cpp hands to the public
// runtime functions, and what they give back, once from a translation unit compiled
// with the project's flags (test_contraction.cpp) and once from one compiled as an
// engine might (contraction_consumer.cpp: -ffp-contract=fast -mfma -O2).
#pragma once

#include "looptess/asset.h"
#include "looptess/runtime.h"

#include <cstdint>
#include <vector>

namespace lt::test {

// An engine's own data: every float made by the caller (test_contraction.cpp), so
// the two translation units start from the same bits.
struct ContractionInputs {
    const Asset* asset = nullptr;
    std::vector<float> uv;                // 2 per point: (u, v) on a base face
    std::vector<float> corners2;          // 6 per point: corner values of width 2 (UVs)
    std::vector<float> corners4;          // 12 per point: corner values of width 4 (colours)
    std::vector<float> pu, pv, n;         // 3 per point: faceTangent's derivatives and unit normal
    std::vector<float> controlPositions;  // 3 per control vertex (posed)
    std::vector<float> editValues;        // 3 per edit, or empty
    std::vector<EvalSettings> settings;   // for evaluateCpu and CpuEvaluator
    float eye[3] = {0, 0, 0};
    std::vector<float> factors;  // for runtimeDepth
    size_t points() const { return uv.size() / 2; }
};

struct ContractionOutputs {
    std::vector<float> attribute2, attribute4, texcoord, tangent;  // per point: 2, 4, 2, 4
    std::vector<Lod> lods;                                         // cameraLod, one per LodMode
    std::vector<float> lodFactors;                                 // lodTessFactor, one per settings
    std::vector<uint32_t> depths;                                  // runtimeDepth (both overloads), per factor
    std::vector<float> subdivided;                                 // subdivideCpu at the asset's maximum depth
    std::vector<float> bakedEdits;                                 // bakedEditValues
    std::vector<Tessellation> evaluated;                           // evaluateCpu, one per settings
    std::vector<Tessellation> reused;                              // one CpuEvaluator, one per settings
    std::vector<uint8_t> drawsPatterns;                            // drawsPatterns, per DrawPath
};

// The same calls (contraction_calls.inc), in the two translation units.
void callsWithProjectFlags(const ContractionInputs& in, ContractionOutputs& out);
void callsAsAnEngine(const ContractionInputs& in, ContractionOutputs& out);  // needs FMA

}  // namespace lt::test
