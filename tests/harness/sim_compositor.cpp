// The compositor: checks the layers of xrEndFrame and, when a frame is captured, composes
// them on the CPU. Each sub-image is copied from its swapchain's latest released image into
// a host-visible buffer on the application's queue; the layers are then blended in order,
// in linear light, over black (the display is opaque).
//
// Projection views fill their eye's view: the runtime's views are the only ones an
// application is given, so a view's fov is taken to be the display's. Quad layers are
// ray-cast from each eye; cube, cylinder and equirect layers are not supported.

#include <array>
#include <cmath>
#include <limits>

#include "sim_runtime.h"

namespace physhand::sim {
namespace {

struct Linear {
    float r, g, b, a;
};

// One sub-image, read back: its rectangle's texels, tightly packed, rows top to bottom.
struct Source {
    const XrCompositionLayerBaseHeader* layer;
    std::optional<std::uint32_t> view;  // the eye of a projection view; nullopt for a quad
    const SwapchainData* swapchain;
    VkImage image;
    XrSwapchainSubImage sub_image;
    VkDeviceSize offset = 0;  // in the readback buffer
    const std::uint8_t* texels = nullptr;
};

XrResult check_sub_image(Runtime& rt, XrSession session, const XrSwapchainSubImage& sub) {
    const SwapchainData* swapchain = rt.swapchains.find(sub.swapchain);
    if (swapchain == nullptr || swapchain->session != session) return XR_ERROR_HANDLE_INVALID;
    // Depth images are never shown (no XR_KHR_composition_layer_depth).
    if (!swapchain->released || swapchain->aspect != VK_IMAGE_ASPECT_COLOR_BIT) {
        return XR_ERROR_LAYER_INVALID;
    }
    if (sub.imageArrayIndex >= swapchain->array_size) return XR_ERROR_VALIDATION_FAILURE;
    const XrRect2Di& rect = sub.imageRect;
    if (rect.offset.x < 0 || rect.offset.y < 0 || rect.extent.width <= 0 ||
        rect.extent.height <= 0 ||
        std::int64_t{rect.offset.x} + rect.extent.width > std::int64_t{swapchain->width} ||
        std::int64_t{rect.offset.y} + rect.extent.height > std::int64_t{swapchain->height}) {
        return XR_ERROR_SWAPCHAIN_RECT_INVALID;
    }
    return XR_SUCCESS;
}

XrResult check_layer(Runtime& rt, XrSession session, const XrCompositionLayerBaseHeader& layer) {
    const SpaceData* space = rt.spaces.find(layer.space);
    if (space == nullptr || space->session != session) return XR_ERROR_HANDLE_INVALID;
    switch (layer.type) {
        case XR_TYPE_COMPOSITION_LAYER_PROJECTION: {
            const auto& projection = reinterpret_cast<const XrCompositionLayerProjection&>(layer);
            if (projection.viewCount != kViewCount || projection.views == nullptr) {
                return XR_ERROR_VALIDATION_FAILURE;
            }
            for (std::uint32_t v = 0; v < kViewCount; ++v) {
                const XrCompositionLayerProjectionView& view = projection.views[v];
                if (view.type != XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW) {
                    return XR_ERROR_VALIDATION_FAILURE;
                }
                if (!is_valid_pose(view.pose)) return XR_ERROR_POSE_INVALID;
                if (XrResult result = check_sub_image(rt, session, view.subImage);
                    XR_FAILED(result)) {
                    return result;
                }
            }
            return XR_SUCCESS;
        }
        case XR_TYPE_COMPOSITION_LAYER_QUAD: {
            const auto& quad = reinterpret_cast<const XrCompositionLayerQuad&>(layer);
            if (quad.eyeVisibility > XR_EYE_VISIBILITY_RIGHT) return XR_ERROR_VALIDATION_FAILURE;
            if (!is_valid_pose(quad.pose)) return XR_ERROR_POSE_INVALID;
            return check_sub_image(rt, session, quad.subImage);
        }
        default:
            return XR_ERROR_LAYER_INVALID;
    }
}

// The sub-images of all layers, in layer order.
std::vector<Source> sources(Runtime& rt, const XrFrameEndInfo& info) {
    std::vector<Source> found;
    auto add = [&](const XrCompositionLayerBaseHeader* layer, std::optional<std::uint32_t> view,
                   const XrSwapchainSubImage& sub) {
        const SwapchainData* swapchain = rt.swapchains.find(sub.swapchain);
        found.push_back(
            {layer, view, swapchain, swapchain->images->images()[*swapchain->released], sub});
    };
    for (std::uint32_t i = 0; i < info.layerCount; ++i) {
        const XrCompositionLayerBaseHeader* layer = info.layers[i];
        if (layer->type == XR_TYPE_COMPOSITION_LAYER_PROJECTION) {
            const auto* projection = reinterpret_cast<const XrCompositionLayerProjection*>(layer);
            for (std::uint32_t v = 0; v < kViewCount; ++v) {
                add(layer, v, projection->views[v].subImage);
            }
        } else {
            add(layer, std::nullopt,
                reinterpret_cast<const XrCompositionLayerQuad*>(layer)->subImage);
        }
    }
    return found;
}

// Copies every source's rectangle into the session's readback buffer. Each image layer
// goes from the layout the application left it in to TRANSFER_SRC and back, once even
// when several sources share it.
void read_back(VulkanSession& vulkan, std::vector<Source>& found) {
    VkDeviceSize size = 0;
    std::vector<VkBufferImageCopy> copies;
    std::vector<VkImageMemoryBarrier> to_transfer, back;
    for (Source& source : found) {
        const XrRect2Di& rect = source.sub_image.imageRect;
        source.offset = size;
        size += VkDeviceSize{4} * rect.extent.width * rect.extent.height;
        VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1,
                                      source.sub_image.imageArrayIndex, 1};
        bool seen = std::any_of(to_transfer.begin(), to_transfer.end(), [&](const auto& b) {
            return b.image == source.image &&
                   b.subresourceRange.baseArrayLayer == range.baseArrayLayer;
        });
        if (!seen) {
            VkImageLayout layout = source.swapchain->layout;
            to_transfer.push_back(
                layout_barrier(source.image, range, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
            back.push_back(
                layout_barrier(source.image, range, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout));
        }
    }
    VkBuffer buffer = vulkan.readback_buffer(size);
    const DeviceFunctions& fn = vulkan.fn();
    vulkan.submit([&](VkCommandBuffer commands) {
        fn.vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                                VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0, nullptr,
                                static_cast<std::uint32_t>(to_transfer.size()), to_transfer.data());
        for (const Source& source : found) {
            const XrRect2Di& rect = source.sub_image.imageRect;
            VkBufferImageCopy copy{};
            copy.bufferOffset = source.offset;
            copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, source.sub_image.imageArrayIndex,
                                     1};
            copy.imageOffset = {rect.offset.x, rect.offset.y, 0};
            copy.imageExtent = {static_cast<std::uint32_t>(rect.extent.width),
                                static_cast<std::uint32_t>(rect.extent.height), 1};
            fn.vkCmdCopyImageToBuffer(commands, source.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                      buffer, 1, &copy);
        }
        // The copies become visible to the host reading the mapped buffer.
        auto to_host = vk_struct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
        to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        fn.vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT,
                                VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, nullptr, 0, nullptr);
        fn.vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                                VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0, nullptr,
                                static_cast<std::uint32_t>(back.size()), back.data());
    });
    for (Source& source : found) source.texels = vulkan.readback_data() + source.offset;
}

float srgb_to_linear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// The 8-bit sRGB code values decoded, and encoding that rounds exactly as the sRGB curve
// does (a code decoded and encoded again comes back unchanged) without a search per value:
// the bins of a table are narrower than the gap between two codes' thresholds, so a bin's
// lower edge gives the code up to one comparison.
struct SrgbTables {
    static constexpr int kBins = 16384;  // 6e-5 wide; thresholds are 3e-4 apart or more
    std::array<float, 256> decode;
    std::array<float, 256> thresholds;  // [i]: the least linear value encoded above i
    std::array<std::uint8_t, kBins> bin_code;

    SrgbTables() {
        for (int i = 0; i < 256; ++i) decode[i] = srgb_to_linear(i / 255.0f);
        for (int i = 0; i < 255; ++i) thresholds[i] = srgb_to_linear((i + 0.5f) / 255.0f);
        thresholds[255] = std::numeric_limits<float>::infinity();
        for (int b = 0; b < kBins; ++b) {
            bin_code[b] = static_cast<std::uint8_t>(
                std::upper_bound(thresholds.begin(), thresholds.end(), float(b) / kBins) -
                thresholds.begin());
        }
    }
    std::uint8_t encode(float linear) const {
        if (!(linear > 0)) return 0;
        if (linear >= 1) return 255;
        std::uint8_t code = bin_code[static_cast<int>(linear * kBins)];
        return code + (linear >= thresholds[code] ? 1 : 0);
    }
};

const SrgbTables& srgb() {
    static const SrgbTables tables;
    return tables;
}

// The texel at (x, y) of a source's rectangle. UNORM formats hold linear values, as the
// OpenXR specification says a compositor must take them.
Linear texel(const Source& source, std::int32_t x, std::int32_t y) {
    const std::uint8_t* p =
        source.texels + 4 * (std::size_t(y) * source.sub_image.imageRect.extent.width + x);
    VkFormat format = source.swapchain->format;
    bool bgra = format == VK_FORMAT_B8G8R8A8_SRGB || format == VK_FORMAT_B8G8R8A8_UNORM;
    bool srgb_encoded = format == VK_FORMAT_R8G8B8A8_SRGB || format == VK_FORMAT_B8G8R8A8_SRGB;
    auto channel = [&](std::uint8_t code) {
        return srgb_encoded ? srgb().decode[code] : code / 255.0f;
    };
    std::uint8_t r = bgra ? p[2] : p[0], b = bgra ? p[0] : p[2];
    return {channel(r), channel(p[1]), channel(b), p[3] / 255.0f};
}

// Layer blending as XrCompositionLayerFlags ask: without source alpha a layer replaces
// what is below; with it, colours are premultiplied unless the layer says otherwise.
void blend(float* rgb, const Linear& s, XrCompositionLayerFlags flags) {
    if ((flags & XR_COMPOSITION_LAYER_BLEND_TEXTURE_SOURCE_ALPHA_BIT) == 0) {
        rgb[0] = s.r, rgb[1] = s.g, rgb[2] = s.b;
        return;
    }
    float k = (flags & XR_COMPOSITION_LAYER_UNPREMULTIPLIED_ALPHA_BIT) != 0 ? s.a : 1.0f;
    rgb[0] = s.r * k + rgb[0] * (1 - s.a);
    rgb[1] = s.g * k + rgb[1] * (1 - s.a);
    rgb[2] = s.b * k + rgb[2] * (1 - s.a);
}

// A linear RGB view being composed.
struct Canvas {
    std::uint32_t width = kViewSize, height = kViewSize;
    std::vector<float> rgb = std::vector<float>(std::size_t{3} * kViewSize * kViewSize, 0.0f);
    float* at(std::uint32_t x, std::uint32_t y) { return &rgb[3 * (std::size_t(y) * width + x)]; }
};

void draw_projection_view(Canvas& canvas, const Source& source) {
    const XrExtent2Di& extent = source.sub_image.imageRect.extent;
    for (std::uint32_t y = 0; y < canvas.height; ++y) {
        auto sy = static_cast<std::int32_t>(std::uint64_t{y} * extent.height / canvas.height);
        for (std::uint32_t x = 0; x < canvas.width; ++x) {
            auto sx = static_cast<std::int32_t>(std::uint64_t{x} * extent.width / canvas.width);
            blend(canvas.at(x, y), texel(source, sx, sy), source.layer->layerFlags);
        }
    }
}

// Casts each pixel's ray from the eye onto the quad's plane (its local z = 0).
void draw_quad(Canvas& canvas, const Source& source, std::uint32_t view,
               const Pose& quad_in_stage) {
    const auto& quad = *reinterpret_cast<const XrCompositionLayerQuad*>(source.layer);
    const Pose eye = eye_in_stage(view);
    const Pose stage_in_quad = quad_in_stage.inverse();
    const Vec3 origin = stage_in_quad * eye.position;
    const Eigen::Matrix3d turn = (stage_in_quad.orientation * eye.orientation).toRotationMatrix();
    const XrFovf fov = eye_fov();
    const double left = std::tan(fov.angleLeft), right = std::tan(fov.angleRight);
    const double up = std::tan(fov.angleUp), down = std::tan(fov.angleDown);
    const XrExtent2Di& extent = source.sub_image.imageRect.extent;
    for (std::uint32_t y = 0; y < canvas.height; ++y) {
        double ty = up + (down - up) * (y + 0.5) / canvas.height;
        for (std::uint32_t x = 0; x < canvas.width; ++x) {
            double tx = left + (right - left) * (x + 0.5) / canvas.width;
            Vec3 direction = turn * Vec3(tx, ty, -1);
            double t = -origin.z() / direction.z();
            if (!(t > 0)) continue;  // parallel to the plane, or behind the eye
            Vec3 hit = origin + t * direction;
            double u = hit.x() / quad.size.width + 0.5;
            double v = 0.5 - hit.y() / quad.size.height;
            if (!(u >= 0 && u < 1 && v >= 0 && v < 1)) continue;
            blend(canvas.at(x, y),
                  texel(source, static_cast<std::int32_t>(u * extent.width),
                        static_cast<std::int32_t>(v * extent.height)),
                  source.layer->layerFlags);
        }
    }
}

bool quad_visible_to(const XrCompositionLayerQuad& quad, std::uint32_t view) {
    return quad.eyeVisibility == XR_EYE_VISIBILITY_BOTH ||
           (quad.eyeVisibility == XR_EYE_VISIBILITY_LEFT && view == 0) ||
           (quad.eyeVisibility == XR_EYE_VISIBILITY_RIGHT && view == 1);
}

Rgba8Image encode(const Canvas& canvas) {
    Rgba8Image image{canvas.width, canvas.height,
                     std::vector<std::uint8_t>(std::size_t{4} * canvas.width * canvas.height)};
    for (std::size_t i = 0; i < std::size_t{canvas.width} * canvas.height; ++i) {
        for (std::size_t c = 0; c < 3; ++c)
            image.pixels[4 * i + c] = srgb().encode(canvas.rgb[3 * i + c]);
        image.pixels[4 * i + 3] = 255;
    }
    return image;
}

}  // namespace

XrResult check_layers(Runtime& rt, XrSession session, const XrFrameEndInfo& info) {
    if (info.layerCount > kMaxLayerCount) return XR_ERROR_LAYER_LIMIT_EXCEEDED;
    // A runtime refusing layers it reported room for, for the tests of what the physhand
    // layer does when its overlay's layer is refused. Read at every frame, so that a test
    // can lift it within a session.
    if (const std::optional<std::int64_t> limit =
            whole_number_env("PHYSHAND_SIM_REJECT_LAYERS_OVER", 0);
        limit && info.layerCount > *limit) {
        return XR_ERROR_LAYER_LIMIT_EXCEEDED;
    }
    for (std::uint32_t i = 0; i < info.layerCount; ++i) {
        if (info.layers[i] == nullptr) return XR_ERROR_LAYER_INVALID;
        if (XrResult result = check_layer(rt, session, *info.layers[i]); XR_FAILED(result)) {
            return result;
        }
    }
    return XR_SUCCESS;
}

std::vector<Rgba8Image> compose_layers(Runtime& rt, XrSession session, const XrFrameEndInfo& info) {
    std::vector<Source> found = sources(rt, info);
    if (!found.empty()) read_back(*rt.sessions.find(session)->vulkan, found);
    std::vector<Rgba8Image> views;
    for (std::uint32_t v = 0; v < kViewCount; ++v) {
        Canvas canvas;
        for (const Source& source : found) {
            if (source.view) {
                if (*source.view == v) draw_projection_view(canvas, source);
                continue;
            }
            const auto& quad = *reinterpret_cast<const XrCompositionLayerQuad*>(source.layer);
            std::optional<Pose> space = space_in_stage(*rt.spaces.find(quad.space));
            if (space && quad_visible_to(quad, v)) {
                draw_quad(canvas, source, v, *space * from_xr(quad.pose));
            }
        }
        views.push_back(encode(canvas));
    }
    return views;
}

}  // namespace physhand::sim
