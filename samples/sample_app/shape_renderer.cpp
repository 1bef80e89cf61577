#include "shape_renderer.h"

#include <algorithm>
#include <cstring>

#include "shape_frag.h"
#include "shape_vert.h"

namespace physhand::sample {

namespace {

// Linear sky; the floor and the shapes stand out against it.
constexpr VkClearColorValue kBackground = {{0.42f, 0.55f, 0.72f, 1.0f}};

// Matches the push-constant block of shape.vert and shape.frag.
struct PushConstants {
    float model_view_projection[16];
    float model[3][4];
    float color[4];
};
static_assert(sizeof(PushConstants) == 128, "the least push-constant room Vulkan guarantees");

// The aspects of a depth image view of `format`: a combined format's attachment is viewed
// whole.
VkImageAspectFlags depth_aspects(VkFormat format) {
    const bool stencil = format == VK_FORMAT_D32_SFLOAT_S8_UINT ||
                         format == VK_FORMAT_D24_UNORM_S8_UINT ||
                         format == VK_FORMAT_D16_UNORM_S8_UINT;
    return VK_IMAGE_ASPECT_DEPTH_BIT | (stencil ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
}

VkRenderPass create_render_pass(VkDevice device, VkFormat color_format, VkFormat depth_format) {
    std::array<VkAttachmentDescription, 2> attachments{};
    attachments[0].format = color_format;
    attachments[0].samples = VK_SAMPLE_COUNT_1_BIT;
    attachments[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    attachments[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachments[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachments[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachments[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // cleared whole
    attachments[0].finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    attachments[1] = attachments[0];
    attachments[1].format = depth_format;
    attachments[1].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachments[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    const VkAttachmentReference color{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    const VkAttachmentReference depth{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &color;
    subpass.pDepthStencilAttachment = &depth;
    // Orders this pass's clears after earlier attachment writes on this queue. The runtime's
    // reads of a colour image are ordered by the swapchain protocol instead: render() waits
    // for its fence before the image is released, and xrWaitSwapchainImage hands an image
    // back only once the runtime is done with it.
    VkSubpassDependency dependency{};
    dependency.srcSubpass = VK_SUBPASS_EXTERNAL;
    dependency.dstSubpass = 0;
    dependency.srcStageMask =
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    dependency.dstStageMask =
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
    dependency.srcAccessMask =
        VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    dependency.dstAccessMask =
        VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    VkRenderPassCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
    info.attachmentCount = static_cast<std::uint32_t>(attachments.size());
    info.pAttachments = attachments.data();
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 1;
    info.pDependencies = &dependency;
    VkRenderPass render_pass = VK_NULL_HANDLE;
    vk_check(vkCreateRenderPass(device, &info, nullptr, &render_pass), "vkCreateRenderPass");
    return render_pass;
}

VkShaderModule shader_module(VkDevice device, const std::uint32_t* code, std::size_t bytes) {
    VkShaderModuleCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    info.codeSize = bytes;
    info.pCode = code;
    VkShaderModule module = VK_NULL_HANDLE;
    vk_check(vkCreateShaderModule(device, &info, nullptr, &module), "vkCreateShaderModule");
    return module;
}

// Opaque: depth tested and written. Translucent: blended over, depth tested only.
VkPipeline create_pipeline(VkDevice device, VkRenderPass render_pass, VkPipelineLayout layout,
                           bool translucent) {
    const VkShaderModule vert = shader_module(device, shape_vert, sizeof(shape_vert));
    const VkShaderModule frag = shader_module(device, shape_frag, sizeof(shape_frag));
    std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
    for (auto& stage : stages) {
        stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
        stage.pName = "main";
    }
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vert;
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = frag;

    const VkVertexInputBindingDescription binding{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
    const std::array<VkVertexInputAttributeDescription, 2> attributes = {{
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
    }};
    VkPipelineVertexInputStateCreateInfo vertex_input{};
    vertex_input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
    vertex_input.vertexBindingDescriptionCount = 1;
    vertex_input.pVertexBindingDescriptions = &binding;
    vertex_input.vertexAttributeDescriptionCount = static_cast<std::uint32_t>(attributes.size());
    vertex_input.pVertexAttributeDescriptions = attributes.data();
    VkPipelineInputAssemblyStateCreateInfo assembly{};
    assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{};
    viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{};
    raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    // Back faces culled, so a translucent shape shows its front surface once.
    raster.cullMode = VK_CULL_MODE_BACK_BIT;
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{};
    multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depth{};
    depth.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
    depth.depthTestEnable = VK_TRUE;
    depth.depthWriteEnable = translucent ? VK_FALSE : VK_TRUE;
    depth.depthCompareOp = VK_COMPARE_OP_LESS;
    VkPipelineColorBlendAttachmentState blend{};
    blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                           VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    blend.blendEnable = translucent ? VK_TRUE : VK_FALSE;
    blend.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
    blend.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    blend.colorBlendOp = VK_BLEND_OP_ADD;
    // The image stays opaque: the app's layer is the scene, not an overlay.
    blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
    blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    blend.alphaBlendOp = VK_BLEND_OP_ADD;
    VkPipelineColorBlendStateCreateInfo blend_state{};
    blend_state.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
    blend_state.attachmentCount = 1;
    blend_state.pAttachments = &blend;
    const std::array<VkDynamicState, 2> dynamic_states = {VK_DYNAMIC_STATE_VIEWPORT,
                                                          VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{};
    dynamic.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
    dynamic.dynamicStateCount = static_cast<std::uint32_t>(dynamic_states.size());
    dynamic.pDynamicStates = dynamic_states.data();

    VkGraphicsPipelineCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
    info.stageCount = static_cast<std::uint32_t>(stages.size());
    info.pStages = stages.data();
    info.pVertexInputState = &vertex_input;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend_state;
    info.pDynamicState = &dynamic;
    info.layout = layout;
    info.renderPass = render_pass;
    VkPipeline pipeline = VK_NULL_HANDLE;
    const VkResult result =
        vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
    vkDestroyShaderModule(device, vert, nullptr);
    vkDestroyShaderModule(device, frag, nullptr);
    vk_check(result, "vkCreateGraphicsPipelines");
    return pipeline;
}

PushConstants push_constants(const Eigen::Matrix4f& view_projection, const Draw& draw) {
    PushConstants push{};
    const Eigen::Matrix4f mvp = view_projection * draw.model;
    std::memcpy(push.model_view_projection, mvp.data(), sizeof(push.model_view_projection));
    for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 3; ++col) push.model[row][col] = draw.model(row, col);
    }
    std::copy(draw.color.begin(), draw.color.end(), push.color);
    return push;
}

}  // namespace

ShapeRenderer::ShapeRenderer(const VulkanDevice& device, VkFormat color_format,
                             const MeshSet& meshes)
    : device_(device), color_format_(color_format) {
    const VkDevice vk = device.device();
    render_pass_ = create_render_pass(vk, color_format, device.depth_format());
    VkPushConstantRange range{};
    range.stageFlags = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    range.size = sizeof(PushConstants);
    VkPipelineLayoutCreateInfo layout_info{};
    layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    layout_info.pushConstantRangeCount = 1;
    layout_info.pPushConstantRanges = &range;
    vk_check(vkCreatePipelineLayout(vk, &layout_info, nullptr, &layout_), "vkCreatePipelineLayout");
    opaque_ = create_pipeline(vk, render_pass_, layout_, false);
    translucent_ = create_pipeline(vk, render_pass_, layout_, true);
    vertices_ = upload(meshes.vertices().data(), meshes.vertices().size() * sizeof(Vertex),
                       VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    indices_ = upload(meshes.indices().data(), meshes.indices().size() * sizeof(std::uint32_t),
                      VK_BUFFER_USAGE_INDEX_BUFFER_BIT);

    VkCommandPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = device.queue_family();
    vk_check(vkCreateCommandPool(vk, &pool_info, nullptr, &pool_), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo allocate{};
    allocate.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    allocate.commandPool = pool_;
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    vk_check(vkAllocateCommandBuffers(vk, &allocate, &commands_), "vkAllocateCommandBuffers");
    VkFenceCreateInfo fence_info{};
    fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    vk_check(vkCreateFence(vk, &fence_info, nullptr, &fence_), "vkCreateFence");
}

ShapeRenderer::~ShapeRenderer() {
    const VkDevice vk = device_.device();
    vkDeviceWaitIdle(vk);
    for (Target& t : targets_) {
        vkDestroyFramebuffer(vk, t.framebuffer, nullptr);
        vkDestroyImageView(vk, t.depth_view, nullptr);
        vkDestroyImage(vk, t.depth, nullptr);
        vkFreeMemory(vk, t.depth_memory, nullptr);
        vkDestroyImageView(vk, t.color_view, nullptr);
    }
    vkDestroyFence(vk, fence_, nullptr);
    vkDestroyCommandPool(vk, pool_, nullptr);
    for (Buffer* b : {&vertices_, &indices_}) {
        vkDestroyBuffer(vk, b->buffer, nullptr);
        vkFreeMemory(vk, b->memory, nullptr);
    }
    vkDestroyPipeline(vk, opaque_, nullptr);
    vkDestroyPipeline(vk, translucent_, nullptr);
    vkDestroyPipelineLayout(vk, layout_, nullptr);
    vkDestroyRenderPass(vk, render_pass_, nullptr);
}

// Host-visible memory: the meshes are small and uploaded once.
ShapeRenderer::Buffer ShapeRenderer::upload(const void* data, VkDeviceSize size,
                                            VkBufferUsageFlags usage) {
    const VkDevice vk = device_.device();
    Buffer result;
    VkBufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = std::max<VkDeviceSize>(size, 4);
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    vk_check(vkCreateBuffer(vk, &info, nullptr, &result.buffer), "vkCreateBuffer");
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(vk, result.buffer, &requirements);
    result.memory = device_.allocate(
        requirements, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    vk_check(vkBindBufferMemory(vk, result.buffer, result.memory, 0), "vkBindBufferMemory");
    void* mapped = nullptr;
    vk_check(vkMapMemory(vk, result.memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
    std::memcpy(mapped, data, size);
    vkUnmapMemory(vk, result.memory);
    return result;
}

VkImageView ShapeRenderer::image_view(VkImage image, VkFormat format, VkImageAspectFlags aspect) {
    VkImageViewCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    info.image = image;
    info.viewType = VK_IMAGE_VIEW_TYPE_2D;
    info.format = format;
    info.subresourceRange = {aspect, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    vk_check(vkCreateImageView(device_.device(), &info, nullptr, &view), "vkCreateImageView");
    return view;
}

// Swapchain images live as long as the session, as does the renderer: targets are made
// once per image and never dropped.
const ShapeRenderer::Target& ShapeRenderer::target(const ViewTarget& view) {
    for (const Target& t : targets_) {
        if (t.image == view.image && t.extent.width == view.extent.width &&
            t.extent.height == view.extent.height) {
            return t;
        }
    }
    const VkDevice vk = device_.device();
    Target t;
    t.image = view.image;
    t.extent = view.extent;
    t.color_view = image_view(view.image, color_format_, VK_IMAGE_ASPECT_COLOR_BIT);
    VkImageCreateInfo depth{};
    depth.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    depth.imageType = VK_IMAGE_TYPE_2D;
    depth.format = device_.depth_format();
    depth.extent = {view.extent.width, view.extent.height, 1};
    depth.mipLevels = 1;
    depth.arrayLayers = 1;
    depth.samples = VK_SAMPLE_COUNT_1_BIT;
    depth.tiling = VK_IMAGE_TILING_OPTIMAL;
    depth.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    depth.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    vk_check(vkCreateImage(vk, &depth, nullptr, &t.depth), "vkCreateImage(depth)");
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(vk, t.depth, &requirements);
    t.depth_memory = device_.allocate(requirements, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    vk_check(vkBindImageMemory(vk, t.depth, t.depth_memory, 0), "vkBindImageMemory");
    t.depth_view =
        image_view(t.depth, device_.depth_format(), depth_aspects(device_.depth_format()));
    const std::array<VkImageView, 2> attachments = {t.color_view, t.depth_view};
    VkFramebufferCreateInfo framebuffer{};
    framebuffer.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    framebuffer.renderPass = render_pass_;
    framebuffer.attachmentCount = static_cast<std::uint32_t>(attachments.size());
    framebuffer.pAttachments = attachments.data();
    framebuffer.width = view.extent.width;
    framebuffer.height = view.extent.height;
    framebuffer.layers = 1;
    vk_check(vkCreateFramebuffer(vk, &framebuffer, nullptr, &t.framebuffer), "vkCreateFramebuffer");
    targets_.push_back(t);
    return targets_.back();
}

void ShapeRenderer::record(VkCommandBuffer commands, const ViewTarget& view,
                           std::span<const Draw> draws) {
    const Target& t = target(view);
    std::array<VkClearValue, 2> clear{};
    clear[0].color = kBackground;
    clear[1].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    begin.renderPass = render_pass_;
    begin.framebuffer = t.framebuffer;
    begin.renderArea = {{0, 0}, t.extent};
    begin.clearValueCount = static_cast<std::uint32_t>(clear.size());
    begin.pClearValues = clear.data();
    vkCmdBeginRenderPass(commands, &begin, VK_SUBPASS_CONTENTS_INLINE);
    const VkViewport viewport{
        0.0f, 0.0f, static_cast<float>(t.extent.width), static_cast<float>(t.extent.height),
        0.0f, 1.0f};
    vkCmdSetViewport(commands, 0, 1, &viewport);
    const VkRect2D scissor{{0, 0}, t.extent};
    vkCmdSetScissor(commands, 0, 1, &scissor);
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(commands, 0, 1, &vertices_.buffer, &offset);
    vkCmdBindIndexBuffer(commands, indices_.buffer, 0, VK_INDEX_TYPE_UINT32);

    std::vector<const Draw*> translucent;
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, opaque_);
    const auto draw = [&](const Draw& d) {
        const PushConstants push = push_constants(view.view_projection, d);
        vkCmdPushConstants(commands, layout_,
                           VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(push), &push);
        vkCmdDrawIndexed(commands, d.mesh.index_count, 1, d.mesh.first_index, d.mesh.vertex_offset,
                         0);
    };
    for (const Draw& d : draws) {
        if (d.color[3] < 1.0f) {
            translucent.push_back(&d);
        } else {
            draw(d);
        }
    }
    const auto distance = [&](const Draw* d) {
        return (d->model.block<3, 1>(0, 3) - view.eye).squaredNorm();
    };
    std::sort(translucent.begin(), translucent.end(),
              [&](const Draw* a, const Draw* b) { return distance(a) > distance(b); });
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, translucent_);
    for (const Draw* d : translucent) draw(*d);
    vkCmdEndRenderPass(commands);
}

void ShapeRenderer::render(std::span<const ViewTarget> views, std::span<const Draw> draws) {
    vk_check(vkResetCommandBuffer(commands_, 0), "vkResetCommandBuffer");
    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vk_check(vkBeginCommandBuffer(commands_, &begin), "vkBeginCommandBuffer");
    for (const ViewTarget& view : views) record(commands_, view, draws);
    vk_check(vkEndCommandBuffer(commands_), "vkEndCommandBuffer");
    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands_;
    vk_check(vkQueueSubmit(device_.queue(), 1, &submit, fence_), "vkQueueSubmit");
    // Waiting here keeps one frame in flight, so the command buffer and depth images are
    // free again at the next call, and the frame time measured includes the rendering.
    vk_check(vkWaitForFences(device_.device(), 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    vk_check(vkResetFences(device_.device(), 1, &fence_), "vkResetFences");
}

}  // namespace physhand::sample
