// looptess/version.h -- the library's version and the version of the baked format's
// layout (EXT_mesh_loop_subdivision's "version"). The top-level CMakeLists.txt reads
// the LOOPTESS_VERSION_* lines: keep each `#define NAME value` on its own line.
#pragma once

#include <cstdint>

#define LOOPTESS_VERSION_MAJOR  0
#define LOOPTESS_VERSION_MINOR  1
#define LOOPTESS_VERSION_PATCH  0
#define LOOPTESS_VERSION_STRING "0.1.0"

// The extension object's "version" that writeAssetGlb writes and readAssetGlb
// accepts (formats/EXT_mesh_loop_subdivision/README.md). A reader refuses any other
// value as Unsupported: assets of another layout must be baked again.
#define LOOPTESS_FORMAT_LAYOUT_VERSION 2

namespace lt {
inline constexpr uint32_t kFormatLayoutVersion = LOOPTESS_FORMAT_LAYOUT_VERSION;
}  // namespace lt
