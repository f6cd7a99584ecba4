// loopcheck --gpu: captures tessellations through the Vulkan runtime on a headless
// device of its own (lavapipe in CI). Private to loopcheck, so looptess_check (and
// its tests, which the sanitizer build runs) never link Vulkan.
#pragma once

#include "looptess/asset.h"
#include "looptess/runtime.h"

#include <functional>
#include <memory>
#include <string>

namespace lt {

class GpuCapture {
public:
    // A headless device (no validation layers), created once per run: its pipelines
    // are compiled on first use and serve every surface of the file after it (on
    // lavapipe a compile is about a third of a second, more than a small mesh's
    // capture). Unsupported without a Vulkan device that can capture (transform
    // feedback).
    static Status create(std::unique_ptr<GpuCapture>& out);
    ~GpuCapture();
    std::string deviceName() const;
    // Uploads `asset` (which must outlive the captures), replacing the one before.
    Status load(const Asset& asset);
    // lt::capture (vulkan_tools.h) of the loaded asset for `eval`: the soup
    // lt::evaluateCpu makes of it, from the device.
    Status capture(const EvalSettings& eval, Tessellation& soup);
    // The same session by session (lt::capture's CaptureSessionFn), each soup handed
    // to `each` as it is read back; sessions of at most `triangles` (0: lt::capture's
    // largest).
    Status capture(const EvalSettings& eval, uint64_t triangles,
                   const std::function<Status(const Tessellation&)>& each);

private:
    struct Impl;
    explicit GpuCapture(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace lt
