// DrawPath::Auto (vulkan.h's pathChoices): which path a frame draws.
#include "surface.h"

namespace lt {

FrameSettings VulkanSurface::Impl::resolved(const FrameSettings& frame) const {
    FrameSettings f = frame;
    if (f.path == DrawPath::Auto) f.path = DrawPath::Patterns;
    return f;
}

uint64_t VulkanSurface::Impl::trialMemory() const { return 0; }

std::vector<VulkanSurface::PathChoice> VulkanSurface::pathChoices() const { return {}; }

} // namespace lt
