// bench/bench_common.h -- what the benchmarks share: their meshes, the machine they
// ran on, and the median of timed runs. No timing policy here.
#pragma once

#include "looptess/tools/baker.h"

#include <string>
#include <vector>

namespace ltbench {

// The control mesh of a bench model, read and checked as loopbake would: spot, bob,
// fandisk (CORPUS/meshes/NAME.obj), duck (CORPUS/gltf/Duck.glb), torus (generated:
// gen_mesh.h's makeTorus with its default parameters, 100,000 triangles) or scan1m
// (generated: scanParams(), 1,000,000 triangles). `source` (optional) says where it
// came from.
lt::Status loadMesh(const std::string& corpus, const std::string& name, lt::InputMesh& mesh,
                    std::string* source = nullptr);

struct Machine {
    int nproc = 0;         // CPUs this process may run on (as nproc prints)
    std::string cpuModel;  // /proc/cpuinfo "model name" of the first CPU
    std::string compiler, buildType, osdVersion, looptessVersion;
};
// This machine and build (`buildType`: the build's CMake configuration).
Machine machineInfo(const std::string& buildType);

// The median of `v` (the mean of the middle two for an even count; 0 when empty).
double median(std::vector<double> v);

}  // namespace ltbench
