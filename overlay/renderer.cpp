#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "gpu_memory.h"
#include "hand_geometry.h"
#include "overlay_renderer.h"
#include "pipeline.h"
#include "projection.h"
#include "render_targets.h"
#include "vk_check.h"
#include "vk_dispatch.h"

namespace physhand::overlay {

namespace {

// Frames recorded while earlier ones may still run on the GPU. A slot (command buffer,
// instance buffer, fence) is reused only after its fence signals, which at two slots
// means waiting for the frame before last: normally long finished.
constexpr size_t kFramesInFlight = 2;

// 22.5 degree steps around and along: outlines within 2% of the radius of a circle
// (under a pixel for a 1 cm joint 20 cm from the eye, 2000 pixels across 100 degrees) for
// 256 triangles a primitive, a cost that software Vulkan (lavapipe: tests, captures)
// feels more than the pixels do.
constexpr int kCapsuleSegments = 16;
constexpr int kCapsuleRingsPerCap = 4;

}  // namespace

struct Renderer::Impl {
    struct FrameSlot {
        VkCommandBuffer commands = VK_NULL_HANDLE;
        VkFence fence = VK_NULL_HANDLE;
        HostBuffer instances;
        uint32_t first_query = 0;  // its two timestamps: start and end
        bool pending = false;      // submitted, fence not yet seen signalled
    };

    DeviceContext context;
    VkQueue queue = VK_NULL_HANDLE;
    VkFormat color_format = VK_FORMAT_UNDEFINED;
    VkFormat depth_format = VK_FORMAT_UNDEFINED;
    VkCommandPool command_pool = VK_NULL_HANDLE;
    std::array<FrameSlot, kFramesInFlight> slots{};
    size_t next_slot = 0;  // also the oldest pending one
    // The capsule mesh's vertices then the box mesh's, then their indices at index_offset.
    HostBuffer mesh;
    VkDeviceSize index_offset = 0;
    uint32_t capsule_index_count = 0;
    uint32_t box_index_count = 0;
    int32_t box_vertex_offset = 0;
    // By final layout. The first was made for COLOR_ATTACHMENT_OPTIMAL and made the
    // pipelines and framebuffers, which are compatible with all the others.
    std::vector<std::pair<VkImageLayout, VkRenderPass>> render_passes;
    Pipelines pipelines;
    std::optional<RenderTargets> targets;
    VkQueryPool timestamps = VK_NULL_HANDLE;  // null when not asked for or not supported
    double timestamp_period_ns = 0.0;
    uint64_t timestamp_mask = 0;
    std::array<PrimitiveInstance, kMaxInstances> staging{};
    Timings timings;

    Impl() = default;
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;
    ~Impl();

    void init(const CreateInfo& info);
    void create_mesh();
    void create_timestamps(uint32_t queue_family_index);
    VkRenderPass render_pass(VkImageLayout final_layout);
    void retire(FrameSlot& slot);
    void wait_idle();
    void record(const FrameSlot& slot, const Frame& frame, DrawCounts counts);
    void submit(FrameSlot& slot);
};

void Renderer::Impl::init(const CreateInfo& info) {
    if (info.physical_device == VK_NULL_HANDLE || info.device == VK_NULL_HANDLE ||
        info.queue == VK_NULL_HANDLE) {
        throw std::invalid_argument("overlay renderer: null physical device, device or queue");
    }
    context.vk = load_vulkan_functions(info.instance, info.get_instance_proc_addr, info.device);
    context.physical_device = info.physical_device;
    context.device = info.device;  // from here on ~Impl destroys whatever exists
    const auto& vk = context.vk;
    vk.vkGetPhysicalDeviceMemoryProperties(context.physical_device, &context.memory_properties);
    queue = info.queue;
    require_color_format(context, info.color_format);
    color_format = info.color_format;
    depth_format = choose_depth_format(context, info.depth_format);

    VkCommandPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pool_info.flags =
        VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = info.queue_family_index;
    PHYSHAND_VK_CHECK(vk.vkCreateCommandPool(context.device, &pool_info, nullptr, &command_pool));
    std::array<VkCommandBuffer, kFramesInFlight> commands{};
    VkCommandBufferAllocateInfo allocate_info{};
    allocate_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    allocate_info.commandPool = command_pool;
    allocate_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate_info.commandBufferCount = kFramesInFlight;
    PHYSHAND_VK_CHECK(vk.vkAllocateCommandBuffers(context.device, &allocate_info, commands.data()));
    for (size_t i = 0; i < kFramesInFlight; ++i) {
        FrameSlot& slot = slots[i];
        slot.commands = commands[i];
        slot.first_query = static_cast<uint32_t>(2 * i);
        VkFenceCreateInfo fence_info{};
        fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
        PHYSHAND_VK_CHECK(vk.vkCreateFence(context.device, &fence_info, nullptr, &slot.fence));
        slot.instances =
            create_host_buffer(context, sizeof(staging), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    }
    create_mesh();
    const VkRenderPass compatible = render_pass(VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    pipelines = create_pipelines(context, compatible);
    targets.emplace(context, color_format, depth_format, compatible, pipelines.resolve_set_layout);
    if (info.gpu_timestamps) {
        create_timestamps(info.queue_family_index);
    }
}

void Renderer::Impl::create_mesh() {
    Mesh both = build_capsule_mesh(kCapsuleSegments, kCapsuleRingsPerCap);
    const Mesh box = build_box_mesh();
    box_vertex_offset = static_cast<int32_t>(both.vertices.size());
    capsule_index_count = static_cast<uint32_t>(both.indices.size());
    box_index_count = static_cast<uint32_t>(box.indices.size());
    both.vertices.insert(both.vertices.end(), box.vertices.begin(), box.vertices.end());
    both.indices.insert(both.indices.end(), box.indices.begin(), box.indices.end());
    const size_t vertex_bytes = both.vertices.size() * sizeof(MeshVertex);
    const size_t index_bytes = both.indices.size() * sizeof(uint16_t);
    mesh = create_host_buffer(context, vertex_bytes + index_bytes,
                              VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    auto* bytes = static_cast<std::byte*>(mesh.mapped);
    std::memcpy(bytes, both.vertices.data(), vertex_bytes);
    std::memcpy(bytes + vertex_bytes, both.indices.data(), index_bytes);
    index_offset = vertex_bytes;
}

void Renderer::Impl::create_timestamps(uint32_t queue_family_index) {
    const auto& vk = context.vk;
    uint32_t family_count = 0;
    vk.vkGetPhysicalDeviceQueueFamilyProperties(context.physical_device, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vk.vkGetPhysicalDeviceQueueFamilyProperties(context.physical_device, &family_count,
                                                families.data());
    const uint32_t valid_bits =
        queue_family_index < family_count ? families[queue_family_index].timestampValidBits : 0;
    if (valid_bits == 0) {
        return;  // this queue cannot time: gpu_ms stays -1
    }
    VkPhysicalDeviceProperties properties;
    vk.vkGetPhysicalDeviceProperties(context.physical_device, &properties);
    timestamp_period_ns = properties.limits.timestampPeriod;
    timestamp_mask = valid_bits >= 64 ? ~uint64_t{0} : (uint64_t{1} << valid_bits) - 1;
    VkQueryPoolCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = 2 * kFramesInFlight;
    PHYSHAND_VK_CHECK(vk.vkCreateQueryPool(context.device, &info, nullptr, &timestamps));
}

Renderer::Impl::~Impl() {
    if (context.device == VK_NULL_HANDLE) {
        return;  // the functions were never loaded, so nothing was created
    }
    const auto& vk = context.vk;
    for (const FrameSlot& slot : slots) {
        if (slot.pending) {
            // A destructor cannot report a lost device; destroying goes ahead regardless.
            vk.vkWaitForFences(context.device, 1, &slot.fence, VK_TRUE, UINT64_MAX);
        }
    }
    targets.reset();
    destroy(context, pipelines);
    for (const auto& [layout, pass] : render_passes) {
        vk.vkDestroyRenderPass(context.device, pass, nullptr);
    }
    destroy(context, mesh);
    for (FrameSlot& slot : slots) {
        vk.vkDestroyFence(context.device, slot.fence, nullptr);
        destroy(context, slot.instances);
    }
    vk.vkDestroyCommandPool(context.device, command_pool, nullptr);  // frees its buffers
    vk.vkDestroyQueryPool(context.device, timestamps, nullptr);
}

VkRenderPass Renderer::Impl::render_pass(VkImageLayout final_layout) {
    for (const auto& [layout, pass] : render_passes) {
        if (layout == final_layout) {
            return pass;
        }
    }
    const VkRenderPass pass = create_render_pass(context, color_format, depth_format, final_layout);
    render_passes.emplace_back(final_layout, pass);
    return pass;
}

void Renderer::Impl::retire(FrameSlot& slot) {
    if (!slot.pending) {
        return;
    }
    const auto& vk = context.vk;
    PHYSHAND_VK_CHECK(vk.vkWaitForFences(context.device, 1, &slot.fence, VK_TRUE, UINT64_MAX));
    slot.pending = false;
    if (timestamps == VK_NULL_HANDLE) {
        return;
    }
    std::array<uint64_t, 2> ticks{};
    if (vk.vkGetQueryPoolResults(context.device, timestamps, slot.first_query, 2, sizeof(ticks),
                                 ticks.data(), sizeof(uint64_t),
                                 VK_QUERY_RESULT_64_BIT) == VK_SUCCESS) {
        timings.gpu_ms = static_cast<double>((ticks[1] - ticks[0]) & timestamp_mask) *
                         timestamp_period_ns * 1e-6;
        ++timings.gpu_frames;
    }
}

void Renderer::Impl::wait_idle() {
    // Oldest first, so gpu_ms ends on the newest frame.
    for (size_t i = 0; i < kFramesInFlight; ++i) {
        retire(slots[(next_slot + i) % kFramesInFlight]);
    }
}

void Renderer::Impl::record(const FrameSlot& slot, const Frame& frame, DrawCounts counts) {
    const auto& vk = context.vk;
    const VkCommandBuffer commands = slot.commands;
    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    PHYSHAND_VK_CHECK(vk.vkBeginCommandBuffer(commands, &begin));
    if (timestamps != VK_NULL_HANDLE) {
        vk.vkCmdResetQueryPool(commands, timestamps, slot.first_query, 2);
        vk.vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps,
                               slot.first_query);
    }
    const VkBuffer vertex_buffers[] = {mesh.buffer, slot.instances.buffer};
    const VkDeviceSize offsets[] = {0, 0};
    vk.vkCmdBindVertexBuffers(commands, 0, 2, vertex_buffers, offsets);
    vk.vkCmdBindIndexBuffer(commands, mesh.buffer, index_offset, VK_INDEX_TYPE_UINT16);
    // The physical hands' capsules then boxes (each on its own mesh), and the ghost's two
    // passes over its capsules.
    const uint32_t physical = counts.physical_capsules + counts.physical_boxes;
    const auto draw_physical = [&] {
        if (physical == 0) return;
        vk.vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines.physical);
        vk.vkCmdDrawIndexed(commands, capsule_index_count, counts.physical_capsules, 0, 0, 0);
        vk.vkCmdDrawIndexed(commands, box_index_count, counts.physical_boxes, capsule_index_count,
                            box_vertex_offset, counts.physical_capsules);
    };
    const auto draw_ghost = [&](VkPipeline pipeline) {
        if (counts.ghost == 0) return;
        vk.vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
        vk.vkCmdDrawIndexed(commands, capsule_index_count, counts.ghost, 0, 0, physical);
    };
    const VkRenderPass pass = render_pass(frame.final_layout);
    const VkDescriptorSet resolve_input = targets->resolve_input();
    for (const View& view : frame.views) {
        const VkClearValue clears[] = {
            {.color = {.float32 = {0.0f, 0.0f, 0.0f, 0.0f}}},  // transparent background
            {.depthStencil = {0.0f, 0}},                       // reversed depth: far
        };
        const VkRect2D area{{0, 0}, view.extent};
        VkRenderPassBeginInfo pass_begin{};
        pass_begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
        pass_begin.renderPass = pass;
        pass_begin.framebuffer = targets->framebuffer(view);
        pass_begin.renderArea = area;
        pass_begin.clearValueCount = 2;
        pass_begin.pClearValues = clears;
        vk.vkCmdBeginRenderPass(commands, &pass_begin, VK_SUBPASS_CONTENTS_INLINE);
        VkViewport viewport{};
        viewport.width = static_cast<float>(view.extent.width);
        viewport.height = static_cast<float>(view.extent.height);
        viewport.maxDepth = 1.0f;
        vk.vkCmdSetViewport(commands, 0, 1, &viewport);
        vk.vkCmdSetScissor(commands, 0, 1, &area);
        const Vec3& eye = view.eye.position;
        const PushConstants constants{view_projection(view.eye), {eye.x, eye.y, eye.z, 1.0f}};
        vk.vkCmdPushConstants(commands, pipelines.draw_layout, VK_SHADER_STAGE_VERTEX_BIT, 0,
                              sizeof(constants), &constants);
        draw_physical();
        draw_ghost(pipelines.ghost_depth);
        draw_ghost(pipelines.ghost_color);
        vk.vkCmdNextSubpass(commands, VK_SUBPASS_CONTENTS_INLINE);
        vk.vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines.resolve);
        vk.vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_GRAPHICS,
                                   pipelines.resolve_layout, 0, 1, &resolve_input, 0, nullptr);
        vk.vkCmdDraw(commands, 3, 1, 0, 0);
        vk.vkCmdEndRenderPass(commands);
    }
    if (timestamps != VK_NULL_HANDLE) {
        vk.vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps,
                               slot.first_query + 1);
    }
    PHYSHAND_VK_CHECK(vk.vkEndCommandBuffer(commands));
}

void Renderer::Impl::submit(FrameSlot& slot) {
    const auto& vk = context.vk;
    VkSubmitInfo info{};
    info.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    info.commandBufferCount = 1;
    info.pCommandBuffers = &slot.commands;
    PHYSHAND_VK_CHECK(vk.vkResetFences(context.device, 1, &slot.fence));
    PHYSHAND_VK_CHECK(vk.vkQueueSubmit(queue, 1, &info, slot.fence));
    slot.pending = true;
    next_slot = (next_slot + 1) % kFramesInFlight;
}

Renderer::Renderer(const CreateInfo& info) : impl_(std::make_unique<Impl>()) {
    impl_->init(info);
}

Renderer::~Renderer() = default;

bool Renderer::render(const Frame& frame) {
    const auto start = std::chrono::steady_clock::now();
    Impl& impl = *impl_;
    const DrawCounts counts = build_instances(frame, impl.staging);
    const bool drawing = counts.total() > 0 && !frame.views.empty();
    if (drawing) {
        for (const View& view : frame.views) {
            if (view.image == VK_NULL_HANDLE || view.extent.width == 0 || view.extent.height == 0) {
                throw std::invalid_argument("overlay renderer: view without image or extent");
            }
        }
        if (!impl.targets->ready_for(frame.views)) {
            // New targets (the first frames of a swapchain) may replace objects that
            // pending frames still use.
            impl.wait_idle();
            impl.targets->prepare(frame.views);
        }
        Impl::FrameSlot& slot = impl.slots[impl.next_slot];
        impl.retire(slot);
        std::memcpy(slot.instances.mapped, impl.staging.data(),
                    counts.total() * sizeof(PrimitiveInstance));
        impl.record(slot, frame, counts);
        impl.submit(slot);
    }
    impl.timings.cpu_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return drawing;
}

void Renderer::wait_idle() {
    impl_->wait_idle();
}

void Renderer::forget_image(VkImage image) {
    impl_->wait_idle();
    impl_->targets->forget(image);
}

VkExtent2D drawn_extent(VkExtent2D view) {
    const double pixels = static_cast<double>(view.width) * view.height;
    if (pixels <= static_cast<double>(kMaxDrawnPixels)) return view;
    const double scale = std::sqrt(static_cast<double>(kMaxDrawnPixels) / pixels);
    return {std::max(1u, static_cast<uint32_t>(view.width * scale)),
            std::max(1u, static_cast<uint32_t>(view.height * scale))};
}

uint64_t Renderer::memory_bytes() const {
    uint64_t bytes = impl_->mesh.memory_size + impl_->targets->memory_bytes();
    for (const auto& slot : impl_->slots) bytes += slot.instances.memory_size;
    return bytes;
}

Timings Renderer::timings() const {
    return impl_->timings;
}

}  // namespace physhand::overlay
