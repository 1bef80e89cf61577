#include "pipeline.h"

#include <cstddef>
#include <cstdint>
#include <span>

// Generated at build time from shaders/ (glslangValidator --vn).
#include "fullscreen_vert.h"
#include "ghost_frag.h"
#include "hand_geometry.h"
#include "primitive_vert.h"
#include "resolve_frag.h"
#include "shade_frag.h"
#include "vk_check.h"

namespace physhand::overlay {

static_assert(kSamples == VK_SAMPLE_COUNT_4_BIT, "resolve.frag averages 4 samples");

VkRenderPass create_render_pass(const DeviceContext& context, VkFormat color_format,
                                VkFormat depth_format, VkImageLayout final_layout) {
    // {flags, format, samples, load, store, stencil load, stencil store, initial, final}
    constexpr VkAttachmentLoadOp kClear = VK_ATTACHMENT_LOAD_OP_CLEAR;
    constexpr VkAttachmentLoadOp kDontLoad = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    constexpr VkAttachmentStoreOp kDontStore = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    const VkAttachmentDescription attachments[] = {
        {0, color_format, kSamples, kClear, kDontStore, kDontLoad, kDontStore,
         VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
        {0, depth_format, kSamples, kClear, kDontStore, kDontLoad, kDontStore,
         VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL},
        // The resolve overwrites every pixel, so the target's old contents (and layout)
        // do not matter.
        {0, color_format, VK_SAMPLE_COUNT_1_BIT, kDontLoad, VK_ATTACHMENT_STORE_OP_STORE, kDontLoad,
         kDontStore, VK_IMAGE_LAYOUT_UNDEFINED, final_layout},
    };
    const VkAttachmentReference samples{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    const VkAttachmentReference depth{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    const VkAttachmentReference samples_input{0, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    const VkAttachmentReference target{2, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpasses[2]{};
    subpasses[0].pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpasses[0].colorAttachmentCount = 1;
    subpasses[0].pColorAttachments = &samples;
    subpasses[0].pDepthStencilAttachment = &depth;
    subpasses[1].pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpasses[1].inputAttachmentCount = 1;
    subpasses[1].pInputAttachments = &samples_input;
    subpasses[1].colorAttachmentCount = 1;
    subpasses[1].pColorAttachments = &target;

    constexpr VkPipelineStageFlags kAttachmentStages =
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
        VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    constexpr VkPipelineStageFlags kColorStage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    constexpr VkAccessFlags kColorWrite = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    // {src subpass, dst subpass, src stages, dst stages, src access, dst access, flags}
    const VkSubpassDependency dependencies[] = {
        // The previous view or frame drew into and resolved from the same multisampled
        // attachments: write after write, write after read.
        {VK_SUBPASS_EXTERNAL, 0, kAttachmentStages | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
         kAttachmentStages, kColorWrite | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
         VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | kColorWrite |
             VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
             VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
         0},
        // Earlier writes to the target image (a previous frame into the same image).
        {VK_SUBPASS_EXTERNAL, 1, kColorStage, kColorStage, kColorWrite, kColorWrite, 0},
        // The resolve reads what subpass 0 drew, pixel by pixel.
        {0, 1, kColorStage, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, kColorWrite,
         VK_ACCESS_INPUT_ATTACHMENT_READ_BIT, VK_DEPENDENCY_BY_REGION_BIT},
        // Lets the caller's later barriers and semaphore waits on the colour attachment
        // stage order after the resolve and the final layout transition.
        {1, VK_SUBPASS_EXTERNAL, kColorStage, kColorStage, kColorWrite, 0, 0},
    };
    VkRenderPassCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
    info.attachmentCount = 3;
    info.pAttachments = attachments;
    info.subpassCount = 2;
    info.pSubpasses = subpasses;
    info.dependencyCount = 4;
    info.pDependencies = dependencies;
    VkRenderPass render_pass = VK_NULL_HANDLE;
    PHYSHAND_VK_CHECK(context.vk.vkCreateRenderPass(context.device, &info, nullptr, &render_pass));
    return render_pass;
}

namespace {

class ShaderModule {
  public:
    ShaderModule(const DeviceContext& context, std::span<const uint32_t> code) : context_(context) {
        VkShaderModuleCreateInfo info{};
        info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
        info.codeSize = code.size_bytes();
        info.pCode = code.data();
        PHYSHAND_VK_CHECK(
            context.vk.vkCreateShaderModule(context.device, &info, nullptr, &module_));
    }
    ~ShaderModule() { context_.vk.vkDestroyShaderModule(context_.device, module_, nullptr); }
    ShaderModule(const ShaderModule&) = delete;
    ShaderModule& operator=(const ShaderModule&) = delete;

    VkShaderModule get() const { return module_; }

  private:
    const DeviceContext& context_;
    VkShaderModule module_ = VK_NULL_HANDLE;
};

// What differs between the pipelines; the rest is common (triangles, dynamic viewport).
struct PipelineState {
    VkPipelineLayout layout = VK_NULL_HANDLE;
    uint32_t subpass = 0;
    VkShaderModule vertex = VK_NULL_HANDLE;
    VkShaderModule fragment = VK_NULL_HANDLE;
    VkPipelineVertexInputStateCreateInfo vertex_input{};
    VkPipelineRasterizationStateCreateInfo rasterization{};
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    const VkPipelineDepthStencilStateCreateInfo* depth_stencil = nullptr;
    VkPipelineColorBlendAttachmentState blend{};
};

VkPipeline build_pipeline(const DeviceContext& context, VkRenderPass render_pass,
                          const PipelineState& state) {
    VkPipelineShaderStageCreateInfo stages[2]{};
    for (VkPipelineShaderStageCreateInfo& stage : stages) {
        stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
        stage.pName = "main";
    }
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = state.vertex;
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = state.fragment;
    VkPipelineInputAssemblyStateCreateInfo input_assembly{};
    input_assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
    input_assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{};
    viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineMultisampleStateCreateInfo multisample{};
    multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
    multisample.rasterizationSamples = state.samples;
    VkPipelineColorBlendStateCreateInfo color_blend{};
    color_blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
    color_blend.attachmentCount = 1;
    color_blend.pAttachments = &state.blend;
    const VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{};
    dynamic.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamic_states;

    VkGraphicsPipelineCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
    info.stageCount = 2;
    info.pStages = stages;
    info.pVertexInputState = &state.vertex_input;
    info.pInputAssemblyState = &input_assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &state.rasterization;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = state.depth_stencil;
    info.pColorBlendState = &color_blend;
    info.pDynamicState = &dynamic;
    info.layout = state.layout;
    info.renderPass = render_pass;
    info.subpass = state.subpass;
    VkPipeline pipeline = VK_NULL_HANDLE;
    PHYSHAND_VK_CHECK(context.vk.vkCreateGraphicsPipelines(context.device, VK_NULL_HANDLE, 1, &info,
                                                           nullptr, &pipeline));
    return pipeline;
}

constexpr VkColorComponentFlags kRgba = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                        VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;

enum class Pass { Physical, GhostDepth, GhostColor };

VkPipeline create_draw_pipeline(const DeviceContext& context, VkRenderPass render_pass,
                                VkPipelineLayout layout, const ShaderModule& vertex,
                                const ShaderModule& fragment, Pass pass) {
    PipelineState state;
    state.layout = layout;
    state.subpass = 0;
    state.vertex = vertex.get();
    state.fragment = fragment.get();

    const VkVertexInputBindingDescription bindings[] = {
        {0, sizeof(MeshVertex), VK_VERTEX_INPUT_RATE_VERTEX},
        {1, sizeof(PrimitiveInstance), VK_VERTEX_INPUT_RATE_INSTANCE},
    };
    constexpr VkFormat kVec4 = VK_FORMAT_R32G32B32A32_SFLOAT;
    const VkVertexInputAttributeDescription attributes[] = {
        {0, 0, kVec4, offsetof(MeshVertex, local)},
        {1, 0, kVec4, offsetof(MeshVertex, normal)},
        {2, 1, kVec4, offsetof(PrimitiveInstance, start)},
        {3, 1, kVec4, offsetof(PrimitiveInstance, end)},
        {4, 1, kVec4, offsetof(PrimitiveInstance, orientation)},
        {5, 1, kVec4, offsetof(PrimitiveInstance, color)},
    };
    state.vertex_input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
    state.vertex_input.vertexBindingDescriptionCount = 2;
    state.vertex_input.pVertexBindingDescriptions = bindings;
    state.vertex_input.vertexAttributeDescriptionCount = 6;
    state.vertex_input.pVertexAttributeDescriptions = attributes;

    const bool ghost = pass != Pass::Physical;
    state.rasterization.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
    state.rasterization.polygonMode = VK_POLYGON_MODE_FILL;
    state.rasterization.cullMode = VK_CULL_MODE_BACK_BIT;
    state.rasterization.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    // Reversed depth: negative moves away from the eye; two units always separate the
    // ghost from a physical surface at the very same place.
    state.rasterization.depthBiasEnable = ghost ? VK_TRUE : VK_FALSE;
    state.rasterization.depthBiasConstantFactor = ghost ? -2.0f : 0.0f;
    state.rasterization.lineWidth = 1.0f;
    state.samples = kSamples;

    VkPipelineDepthStencilStateCreateInfo depth_stencil{};
    depth_stencil.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
    depth_stencil.depthTestEnable = VK_TRUE;
    depth_stencil.depthWriteEnable = pass == Pass::GhostColor ? VK_FALSE : VK_TRUE;
    depth_stencil.depthCompareOp =
        pass == Pass::GhostColor ? VK_COMPARE_OP_EQUAL : VK_COMPARE_OP_GREATER;
    state.depth_stencil = &depth_stencil;

    state.blend.blendEnable = pass == Pass::GhostColor ? VK_TRUE : VK_FALSE;
    // Premultiplied "over".
    state.blend.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
    state.blend.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    state.blend.colorBlendOp = VK_BLEND_OP_ADD;
    state.blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    state.blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    state.blend.alphaBlendOp = VK_BLEND_OP_ADD;
    state.blend.colorWriteMask = pass == Pass::GhostDepth ? 0u : kRgba;
    return build_pipeline(context, render_pass, state);
}

VkPipeline create_resolve_pipeline(const DeviceContext& context, VkRenderPass render_pass,
                                   VkPipelineLayout layout, const ShaderModule& vertex,
                                   const ShaderModule& fragment) {
    PipelineState state;
    state.layout = layout;
    state.subpass = 1;
    state.vertex = vertex.get();
    state.fragment = fragment.get();
    state.vertex_input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
    state.rasterization.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
    state.rasterization.polygonMode = VK_POLYGON_MODE_FILL;
    state.rasterization.cullMode = VK_CULL_MODE_NONE;
    state.rasterization.lineWidth = 1.0f;
    state.blend.colorWriteMask = kRgba;
    return build_pipeline(context, render_pass, state);
}

}  // namespace

Pipelines create_pipelines(const DeviceContext& context, VkRenderPass render_pass) {
    const auto& vk = context.vk;
    Pipelines result;
    try {
        const VkPushConstantRange push_constants{VK_SHADER_STAGE_VERTEX_BIT, 0,
                                                 sizeof(PushConstants)};
        VkPipelineLayoutCreateInfo draw_layout_info{};
        draw_layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
        draw_layout_info.pushConstantRangeCount = 1;
        draw_layout_info.pPushConstantRanges = &push_constants;
        PHYSHAND_VK_CHECK(vk.vkCreatePipelineLayout(context.device, &draw_layout_info, nullptr,
                                                    &result.draw_layout));
        const ShaderModule primitive(context, primitive_vert);
        const ShaderModule shade(context, shade_frag);
        const ShaderModule ghost(context, ghost_frag);
        result.physical = create_draw_pipeline(context, render_pass, result.draw_layout, primitive,
                                               shade, Pass::Physical);
        result.ghost_depth = create_draw_pipeline(context, render_pass, result.draw_layout,
                                                  primitive, ghost, Pass::GhostDepth);
        result.ghost_color = create_draw_pipeline(context, render_pass, result.draw_layout,
                                                  primitive, ghost, Pass::GhostColor);

        const VkDescriptorSetLayoutBinding input{0, VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT, 1,
                                                 VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
        VkDescriptorSetLayoutCreateInfo set_info{};
        set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
        set_info.bindingCount = 1;
        set_info.pBindings = &input;
        PHYSHAND_VK_CHECK(vk.vkCreateDescriptorSetLayout(context.device, &set_info, nullptr,
                                                         &result.resolve_set_layout));
        VkPipelineLayoutCreateInfo resolve_layout_info{};
        resolve_layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
        resolve_layout_info.setLayoutCount = 1;
        resolve_layout_info.pSetLayouts = &result.resolve_set_layout;
        PHYSHAND_VK_CHECK(vk.vkCreatePipelineLayout(context.device, &resolve_layout_info, nullptr,
                                                    &result.resolve_layout));
        const ShaderModule fullscreen(context, fullscreen_vert);
        const ShaderModule resolve(context, resolve_frag);
        result.resolve = create_resolve_pipeline(context, render_pass, result.resolve_layout,
                                                 fullscreen, resolve);
    } catch (...) {
        destroy(context, result);
        throw;
    }
    return result;
}

void destroy(const DeviceContext& context, Pipelines& pipelines) {
    const auto& vk = context.vk;
    for (const VkPipeline pipeline :
         {pipelines.physical, pipelines.ghost_depth, pipelines.ghost_color, pipelines.resolve}) {
        vk.vkDestroyPipeline(context.device, pipeline, nullptr);
    }
    vk.vkDestroyPipelineLayout(context.device, pipelines.draw_layout, nullptr);
    vk.vkDestroyPipelineLayout(context.device, pipelines.resolve_layout, nullptr);
    vk.vkDestroyDescriptorSetLayout(context.device, pipelines.resolve_set_layout, nullptr);
    pipelines = {};
}

}  // namespace physhand::overlay
