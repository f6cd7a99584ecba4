// loopcheck --gpu (gpu_capture.h).
#include "gpu_capture.h"

#include "looptess/tools/vulkan_tools.h"

#include <algorithm>
#include <cassert>

namespace lt {

struct GpuCapture::Impl {
    std::unique_ptr<VulkanContext> context;
    std::unique_ptr<VulkanSurface> surface;  // destroyed before its context
    ~Impl() { surface.reset(); }
};

GpuCapture::GpuCapture(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
GpuCapture::~GpuCapture() = default;

Status GpuCapture::create(std::unique_ptr<GpuCapture>& out) {
    auto impl = std::make_unique<Impl>();
    if (Status st = VulkanContext::createHeadless(HeadlessOptions{}, impl->context); !st) return st;
    if (!canCapture(*impl->context))
        return Status::error(Status::Unsupported,
                             impl->context->deviceName() + " cannot capture (no transform feedback)");
    out.reset(new GpuCapture(std::move(impl)));
    return Status::ok();
}

Status GpuCapture::load(const Asset& asset) {
    impl_->surface.reset();  // its buffers go before the next asset's are made
    return VulkanSurface::create(*impl_->context, asset, impl_->surface);
}

std::string GpuCapture::deviceName() const { return impl_->context->deviceName(); }

Status GpuCapture::capture(const EvalSettings& eval, Tessellation& soup) {
    assert(impl_->surface && "load an asset first");
    return lt::capture(*impl_->surface, FrameSettings{eval}, soup);
}

Status GpuCapture::capture(const EvalSettings& eval, uint64_t triangles,
                           const std::function<Status(const Tessellation&)>& each) {
    assert(impl_->surface && "load an asset first");
    const uint64_t bytes = triangles ? std::min(kMaxCaptureSessionBytes, triangles * 3 * 84) : kMaxCaptureSessionBytes;
    return lt::capture(
        *impl_->surface, FrameSettings{eval}, [&](const Tessellation& s, size_t) { return each(s); }, nullptr, bytes);
}

}  // namespace lt
