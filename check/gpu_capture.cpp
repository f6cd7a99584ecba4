// loopcheck --gpu (gpu_capture.h).
#include "gpu_capture.h"

#include "looptess/vulkan.h"

namespace lt {

struct GpuCapture::Impl {
    std::unique_ptr<VulkanContext> context;
    std::unique_ptr<VulkanSurface> surface;  // destroyed before its context
    ~Impl() { surface.reset(); }
};

GpuCapture::GpuCapture(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
GpuCapture::~GpuCapture() = default;

Status GpuCapture::create(const Asset& asset, std::unique_ptr<GpuCapture>& out) {
    auto impl = std::make_unique<Impl>();
    if (Status st = VulkanContext::createHeadless(HeadlessOptions{}, impl->context); !st) return st;
    if (!impl->context->canCapture())
        return Status::error(Status::Unsupported, impl->context->deviceName() + " cannot capture (no transform feedback)");
    if (Status st = VulkanSurface::create(*impl->context, asset, impl->surface); !st) return st;
    out.reset(new GpuCapture(std::move(impl)));
    return Status::ok();
}

std::string GpuCapture::deviceName() const { return impl_->context->deviceName(); }

Status GpuCapture::capture(const EvalSettings& eval, Tessellation& soup) {
    FrameSettings frame;
    frame.tessFactor = eval.tessFactor;
    frame.spacing = eval.spacing;
    frame.path = eval.path;
    frame.lod = eval.lod;
    frame.watertight = eval.watertight;
    frame.displace = eval.displace;
    return impl_->surface->capture(frame, soup);
}

} // namespace lt
