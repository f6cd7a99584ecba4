// DrawPath::Auto (vulkan.h's pathChoices and drawnPath): which path a frame draws.
//
// Per level-of-detail mode and depth (a range of factors), the first frames carry a
// trial each: after the frame's subdivision, every path the device has draws the
// frame into a small image of the surface's own, between timestamps written outside
// rendering, in an order rotated from trial to trial:
//
//   subdivide | ts | path A's draws | ts | path B's | ts | path C's | ts | the frame's own draws
//
// The timestamps are read when a later frame (recordSubdivision, renderImage) finds
// them available, never waiting. Once every path has kTrials times, the one with the
// least median is kept; until then frames draw with DrawPath::Patterns. Without
// timestamps on the queue, Compute is kept at once.
#include "render_target.h"

#include <algorithm>
#include <map>

namespace lt {
namespace {

constexpr uint32_t kTrials = 3;       // trial frames a path is measured in
constexpr uint32_t kSlots = 8;        // trials whose timestamps may be pending at once
constexpr uint32_t kSlotQueries = 4;  // timestamps of a trial (three paths at most)
constexpr uint32_t kTrialSize = 256;  // the trial image's width and height
const float kBlack[4] = {0, 0, 0, 0};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

}  // namespace

struct VulkanSurface::Impl::AutoState {
    using Key = std::pair<LodMode, uint32_t>;  // level-of-detail mode, depth
    struct Entry {
        PathChoice choice;
        std::vector<DrawPath> candidates;
        std::vector<double> samples[3];  // by DrawPath (Tessellator, Patterns, Compute)
        uint32_t recorded = 0;           // trials recorded
    };
    struct Pending {
        Key key;
        uint32_t slot;
        std::vector<DrawPath> order;
    };
    std::map<Key, Entry> entries;
    std::vector<Pending> pending;
    std::unique_ptr<RenderTarget> target;
    vk::raii::QueryPool queries{nullptr};
    uint32_t nextSlot = 0;
};

VulkanSurface::Impl::Impl(VulkanContext::Impl& context) : ctx(context) {}
VulkanSurface::Impl::~Impl() = default;

VulkanSurface::Impl::AutoState::Key autoKey(const VulkanSurface::Impl& s, const FrameSettings& frame) {
    return {frame.lod.mode, s.depthFor(s.factorFor(frame))};
}

FrameSettings VulkanSurface::Impl::resolved(const FrameSettings& frame) const {
    FrameSettings f = frame;
    if (f.path != DrawPath::Auto) return f;
    f.path = DrawPath::Patterns;
    if (autoState) {
        auto it = autoState->entries.find(autoKey(*this, frame));
        if (it != autoState->entries.end() && it->second.choice.decided) f.path = it->second.choice.kept;
    }
    return f;
}

uint64_t VulkanSurface::Impl::trialMemory() const {
    if (!autoState || !autoState->target) return 0;
    return autoState->target->color.bytes + autoState->target->zbuffer.bytes;
}

void VulkanSurface::Impl::collectTrials() {
    if (!autoState) return;
    AutoState& a = *autoState;
    for (size_t i = 0; i < a.pending.size();) {
        const AutoState::Pending& p = a.pending[i];
        const uint32_t count = uint32_t(p.order.size()) + 1;
        auto [result, stamps] =
            a.queries.getResults<uint64_t>(p.slot * kSlotQueries, count, count * 8, 8, vk::QueryResultFlagBits::e64);
        if (result != vk::Result::eSuccess) {  // not yet available
            ++i;
            continue;
        }
        AutoState::Entry& e = a.entries[p.key];
        const uint64_t mask = ctx.timestampBits >= 64 ? ~uint64_t(0) : (uint64_t(1) << ctx.timestampBits) - 1;
        for (size_t k = 0; k < p.order.size(); ++k)
            e.samples[size_t(p.order[k])].push_back(double((stamps[k + 1] - stamps[k]) & mask) *
                                                    double(ctx.properties.limits.timestampPeriod) * 1e-6);
        a.pending.erase(a.pending.begin() + std::ptrdiff_t(i));
    }
    for (auto& [key, e] : a.entries) {
        if (e.choice.decided) continue;
        bool complete = true;
        for (DrawPath path : e.candidates) complete = complete && e.samples[size_t(path)].size() >= kTrials;
        if (!complete) continue;
        double best = 0;
        for (DrawPath path : e.candidates) {
            const double ms = median(e.samples[size_t(path)]);
            e.choice.ms[size_t(path)] = ms;
            if (!e.choice.decided || ms < best) {
                e.choice.decided = true;
                e.choice.kept = path;
                best = ms;
            }
        }
        e.choice.trials = uint32_t(e.samples[size_t(e.candidates.front())].size());
    }
    if (a.pending.empty()) {  // nothing measuring: the image goes while every range is decided
        bool undecided = false;
        for (const auto& entry : a.entries) undecided = undecided || !entry.second.choice.decided;
        if (!undecided) a.target.reset();
    }
}

void VulkanSurface::Impl::recordTrial(const vk::raii::CommandBuffer& cmd, const FrameSettings& frame) {
    if (frame.path != DrawPath::Auto) return;
    if (!autoState) autoState = std::make_unique<AutoState>();
    AutoState& a = *autoState;
    const AutoState::Key key = autoKey(*this, frame);
    AutoState::Entry& e = a.entries[key];
    if (e.candidates.empty()) {
        e.choice.mode = key.first;
        e.choice.depth = key.second;
        if (ctx.tessellation) e.candidates.push_back(DrawPath::Tessellator);
        if (frame.lod.mode != LodMode::Screen || ctx.drawIndirectFirstInstance)
            e.candidates.push_back(DrawPath::Patterns);
        e.candidates.push_back(DrawPath::Compute);
        if (ctx.timestampBits == 0) {  // nothing to measure with
            e.choice.decided = true;
            e.choice.kept = DrawPath::Compute;
        }
    }
    if (e.choice.decided || e.recorded >= kTrials + 2 || a.pending.size() >= kSlots) return;
    if (!a.target) {
        a.target = std::make_unique<RenderTarget>(ctx, kTrialSize, kTrialSize);
        if (!*a.queries)
            a.queries = vk::raii::QueryPool(
                ctx.device, vk::QueryPoolCreateInfo({}, vk::QueryType::eTimestamp, kSlots * kSlotQueries));
    }
    uint32_t slot = a.nextSlot++ % kSlots;
    auto used = [&](uint32_t s) {
        return std::any_of(a.pending.begin(), a.pending.end(),
                           [&](const AutoState::Pending& p) { return p.slot == s; });
    };
    while (used(slot)) slot = a.nextSlot++ % kSlots;
    std::vector<DrawPath> order = e.candidates;
    std::rotate(order.begin(), order.begin() + std::ptrdiff_t(e.recorded % order.size()), order.end());
    cmd.resetQueryPool(*a.queries, slot * kSlotQueries, kSlotQueries);
    // Whatever read or wrote the surface's buffers before (the frame's passes, the
    // paths before) is done before each path starts, and each path alone is timed.
    auto settle = [&] {
        memoryBarrier(cmd, vk::PipelineStageFlagBits::eAllCommands,
                      vk::AccessFlagBits::eShaderWrite | vk::AccessFlagBits::eTransferWrite,
                      vk::PipelineStageFlagBits::eAllCommands,
                      vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite |
                          vk::AccessFlagBits::eIndirectCommandRead | vk::AccessFlagBits::eIndexRead |
                          vk::AccessFlagBits::eTransferRead | vk::AccessFlagBits::eTransferWrite);
    };
    for (size_t k = 0; k < order.size(); ++k) {
        FrameSettings f = frame;
        f.path = order[k];
        const DrawPlan plan = planFor(f);  // a copy: the next path's planFor replaces the cached one
        settle();
        cmd.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *a.queries, slot * kSlotQueries + uint32_t(k));
        a.target->prepare(cmd);
        recordTargetDraws(*this, cmd, plan, f, *a.target, kBlack, nullptr);
    }
    settle();
    cmd.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *a.queries,
                       slot * kSlotQueries + uint32_t(order.size()));
    a.pending.push_back({key, slot, order});
    ++e.recorded;
}

std::vector<VulkanSurface::PathChoice> VulkanSurface::pathChoices() const {
    std::vector<PathChoice> out;
    if (impl_->autoState)
        for (const auto& entry : impl_->autoState->entries) out.push_back(entry.second.choice);
    return out;
}

DrawPath VulkanSurface::drawnPath(const FrameSettings& frame) const {
    try {
        return impl_->resolved(frame).path;
    } catch (...) {  // an invalid level of detail: recordDraw reports it
        return frame.path == DrawPath::Auto ? DrawPath::Patterns : frame.path;
    }
}

}  // namespace lt
