// runtime/src/face_attributes.cpp -- runtime.h's surface attribute functions, out of
// line so that they are compiled here, with the library's -ffp-contract=off, and an
// engine calling them gets the CPU evaluator's bits whatever its own flags
// (tests/runtime/test_contraction.cpp). The arithmetic: face_attributes.h.
#include "face_attributes.h"

#include "looptess/runtime.h"

namespace lt {

void faceAttribute(const float* c, int width, float u, float v, float* out) {
    detail::faceAttribute(c, width, u, v, out);
}

void faceTexcoord(const float c[6], float u, float v, float st[2]) { detail::faceTexcoord(c, u, v, st); }

void faceTangent(const float c[6], const float pu[3], const float pv[3], const float n[3], float out[4]) {
    detail::faceTangent(c, pu, pv, n, out);
}

void unitNormal(const float n[3], float out[3]) { detail::unitVector(n, out); }

}  // namespace lt
