// formats/internal/reader.h -- private to looptess_formats and its tests: the GLB
// reader with its thread count stated, so that tests can compare thread counts.
#pragma once

#include "looptess/asset.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lt::fmt {

// lt::readSceneGlb, its level tables decoded and checked on up to `threads` threads
// (0: one per core for large tables, else the calling thread; a compressed stream
// keeps its own rule, decodeStream). Same surfaces and same status for every
// `threads`.
Status readSceneGlb(const uint8_t* data, size_t size, const std::string& name, std::vector<SceneSurface>& surfaces,
                    size_t threads);

}  // namespace lt::fmt
