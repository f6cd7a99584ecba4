// Private to looptess_formats: the container layer of this format's GLB (spec rules
// 1, 2, 3), the first step of readAssetGlb (glb_read.cpp). Safe on untrusted bytes.
#pragma once

#include "looptess/asset.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

namespace lt {

struct GlbContainer {
    nlohmann::json json;           // the JSON chunk, an object with asset.version "2.0"
    const uint8_t* bin = nullptr;  // the BIN chunk (into the caller's bytes), or null
    uint64_t binLength = 0;
};

// readGlb with GlbLayout::Strict (looptess/glb.h), whose faults are rules 1 (header)
// and 2 (chunks); then pre-scans the JSON chunk's nesting (bounded recursion) and
// parses it (rule 3). Errors name `name` and the rule: "<name>: rule 2: GLB chunk 1: ...".
Status readGlbContainer(const uint8_t* data, size_t size, const std::string& name, GlbContainer& out);

}  // namespace lt
