# Every dependency comes from a Debian 12 package (scripts/setup-debian.sh).

find_package(Threads REQUIRED)
find_package(TinyGLTF REQUIRED)
find_package(nlohmann_json 3 REQUIRED)

# OpenSubdiv's packaged CMake config names static libraries Debian does not ship.
find_path(OPENSUBDIV_INCLUDE_DIR opensubdiv/far/topologyRefiner.h REQUIRED)
find_library(OPENSUBDIV_CPU_LIBRARY osdCPU REQUIRED)
add_library(looptess_opensubdiv INTERFACE)
target_include_directories(looptess_opensubdiv SYSTEM INTERFACE ${OPENSUBDIV_INCLUDE_DIR})
target_link_libraries(looptess_opensubdiv INTERFACE ${OPENSUBDIV_CPU_LIBRARY})

# Draco exports symbols of its own older tinygltf copy: whoever links both must
# put TinyGLTF first. Only the baker's glTF input links draco.
find_package(draco REQUIRED)

# Zstandard: the extension's compressed table streams (formats/src/stream.cpp).
find_path(ZSTD_INCLUDE_DIR zstd.h REQUIRED)
find_library(ZSTD_LIBRARY zstd REQUIRED)
add_library(looptess_zstd INTERFACE)
target_include_directories(looptess_zstd SYSTEM INTERFACE ${ZSTD_INCLUDE_DIR})
target_link_libraries(looptess_zstd INTERFACE ${ZSTD_LIBRARY})
