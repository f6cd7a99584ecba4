// runComputeProbe (compute_probe.h).
#include "compute_probe.h"

#include "vulkan/context.h"
#include "vulkan/pipelines.h"

#include <array>
#include <cstring>

namespace lt::test {

std::vector<float> runComputeProbe(VulkanContext& context, const uint32_t* spirv, size_t bytes,
                                   const std::vector<uint32_t>& words, uint32_t base, size_t outputs) {
    VulkanContext::Impl& ctx = VulkanAccess::context(context);
    PushConstants pc;
    pc.base = base;
    const vk::raii::Device& device = ctx.device;
    const auto storage = vk::BufferUsageFlagBits::eStorageBuffer;
    GpuBuffer input = ctx.createBuffer(std::max<size_t>(words.size(), 1) * 4,
                                       storage | vk::BufferUsageFlagBits::eTransferDst, MemoryKind::DeviceLocal);
    if (!words.empty()) ctx.upload(input, words.data(), words.size() * 4);
    GpuBuffer out = ctx.createBuffer(std::max<size_t>(outputs, 1) * 4, storage, MemoryKind::HostVisible);
    GpuBuffer unused = ctx.createBuffer(16, storage, MemoryKind::DeviceLocal);  // binding LT_BINDING_LIMIT

    std::array<vk::DescriptorSetLayoutBinding, 3> bindings;
    const uint32_t numbers[3] = {LT_BINDING_TABLES, LT_BINDING_VERTICES, LT_BINDING_LIMIT};
    for (int i = 0; i < 3; ++i)
        bindings[i] = {numbers[i], vk::DescriptorType::eStorageBuffer, 1, vk::ShaderStageFlagBits::eCompute};
    vk::raii::DescriptorSetLayout setLayout(device, vk::DescriptorSetLayoutCreateInfo({}, bindings));
    vk::PushConstantRange range(vk::ShaderStageFlagBits::eCompute, 0, sizeof(PushConstants));
    vk::raii::PipelineLayout layout(device, vk::PipelineLayoutCreateInfo({}, *setLayout, range));
    vk::raii::ShaderModule module(device, vk::ShaderModuleCreateInfo({}, bytes, spirv));
    vk::raii::Pipeline pipeline(
        device, nullptr,
        vk::ComputePipelineCreateInfo({}, {{}, vk::ShaderStageFlagBits::eCompute, *module, "main"}, *layout));
    vk::DescriptorPoolSize poolSize(vk::DescriptorType::eStorageBuffer, 3);
    vk::raii::DescriptorPool pool(
        device, vk::DescriptorPoolCreateInfo(vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet, 1, poolSize));
    vk::raii::DescriptorSets sets(device, vk::DescriptorSetAllocateInfo(*pool, *setLayout));
    const vk::DescriptorBufferInfo infos[3] = {
        {*input.buffer, 0, VK_WHOLE_SIZE}, {*out.buffer, 0, VK_WHOLE_SIZE}, {*unused.buffer, 0, VK_WHOLE_SIZE}};
    std::array<vk::WriteDescriptorSet, 3> writes;
    for (int i = 0; i < 3; ++i) writes[i] = {*sets[0], numbers[i], 0, vk::DescriptorType::eStorageBuffer, {}, infos[i]};
    device.updateDescriptorSets(writes, {});

    ctx.submitAndWait([&](const vk::raii::CommandBuffer& cmd) {
        cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline);
        cmd.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *layout, 0, *sets[0], {});
        cmd.pushConstants<PushConstants>(*layout, vk::ShaderStageFlagBits::eCompute, 0, pc);
        cmd.dispatch(uint32_t((outputs + LT_LOCAL_SIZE - 1) / LT_LOCAL_SIZE), 1, 1);
        memoryBarrier(cmd, vk::PipelineStageFlagBits::eComputeShader, vk::AccessFlagBits::eShaderWrite,
                      vk::PipelineStageFlagBits::eHost, vk::AccessFlagBits::eHostRead);
    });
    std::vector<float> result(outputs);
    if (outputs) std::memcpy(result.data(), out.mapped, outputs * 4);
    return result;
}

}  // namespace lt::test
