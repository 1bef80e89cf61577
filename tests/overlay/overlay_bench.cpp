// physhand-overlay-bench: times the overlay renderer on the first Vulkan device (set
// VK_ICD_FILENAMES to pick one) drawing the demo hands (physics_hands.h) into a stereo
// array image for views of --size (drawn at overlay::drawn_extent of it, as the layer
// does), and prints one JSON object: median and p99 of the CPU time of render() and of the
// GPU time between its timestamps, in milliseconds, and the renderer's device memory.
//
//   physhand-overlay-bench [--frames N] [--size WIDTH HEIGHT]

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include "headless_vulkan.h"
#include "overlay_renderer.h"
#include "physics_hands.h"

namespace {

using physhand::overlay::CreateInfo;
using physhand::overlay::Renderer;
using physhand::overlay::View;
using namespace physhand::overlay::testing;

double percentile(std::vector<double> values, double p) {
    if (values.empty()) {
        return -1.0;
    }
    std::sort(values.begin(), values.end());
    const auto index = static_cast<size_t>(p * static_cast<double>(values.size() - 1) + 0.5);
    return values[index];
}

int usage() {
    std::cerr << "usage: physhand-overlay-bench [--frames N] [--size WIDTH HEIGHT]\n";
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    int frames = 300;
    VkExtent2D extent{1024, 1024};
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--frames") == 0 && i + 1 < argc) {
            frames = std::atoi(argv[++i]);
        } else if (std::strcmp(argv[i], "--size") == 0 && i + 2 < argc) {
            extent.width = static_cast<uint32_t>(std::atoi(argv[++i]));
            extent.height = static_cast<uint32_t>(std::atoi(argv[++i]));
        } else {
            return usage();
        }
    }
    if (frames <= 0 || extent.width == 0 || extent.height == 0) {
        return usage();
    }

    const VkExtent2D view_extent = extent;
    extent = physhand::overlay::drawn_extent(view_extent);
    std::string reason;
    const auto vulkan = HeadlessVulkan::create(false, nullptr, reason);
    if (!vulkan) {
        std::cerr << "physhand-overlay-bench: " << reason << "\n";
        return 1;
    }
    OffscreenImage image = vulkan->create_image(VK_FORMAT_R8G8B8A8_SRGB, extent, 2);
    vulkan->fill(image, {0, 0, 0, 0}, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    {
        CreateInfo info;
        info.instance = vulkan->instance();
        info.physical_device = vulkan->physical_device();
        info.device = vulkan->device();
        info.queue_family_index = vulkan->queue_family();
        info.queue = vulkan->queue();
        info.gpu_timestamps = true;
        Renderer renderer(info);

        constexpr float kHalfFov = 50.0f * std::numbers::pi_v<float> / 180.0f;
        std::vector<View> views(2);
        for (uint32_t i = 0; i < 2; ++i) {
            views[i].eye.position = {i == 0 ? -0.032f : 0.032f, 0.0f, 0.0f};
            views[i].eye.angle_left = views[i].eye.angle_down = -kHalfFov;
            views[i].eye.angle_right = views[i].eye.angle_up = kHalfFov;
            views[i].image = image.image;
            views[i].array_layer = i;
            views[i].extent = extent;
        }
        physhand::overlay::Frame frame = demo_frame(views);

        // As in an app's frame loop: render, then wait for the frame before the next
        // (the compositor would), which also collects that frame's GPU time.
        std::vector<double> cpu_ms, gpu_ms;
        for (int i = 0; i < frames + 10; ++i) {
            renderer.render(frame);
            renderer.wait_idle();
            if (i >= 10) {  // warm-up: first-use views and framebuffers
                cpu_ms.push_back(renderer.timings().cpu_ms);
                gpu_ms.push_back(renderer.timings().gpu_ms);
            }
        }
        std::printf(
            "{\"device\": \"%s\", \"width\": %u, \"height\": %u, \"drawn_width\": %u, "
            "\"drawn_height\": %u, \"views\": 2, \"frames\": %d, \"cpu_ms_median\": %.4f, "
            "\"cpu_ms_p99\": %.4f, \"gpu_ms_median\": %.4f, \"gpu_ms_p99\": %.4f, "
            "\"memory_mb\": %.1f}\n",
            vulkan->device_name().c_str(), view_extent.width, view_extent.height, extent.width,
            extent.height, frames, percentile(cpu_ms, 0.5), percentile(cpu_ms, 0.99),
            percentile(gpu_ms, 0.5), percentile(gpu_ms, 0.99),
            static_cast<double>(renderer.memory_bytes()) / (1024.0 * 1024.0));
    }
    vulkan->destroy_image(image);
    return 0;
}
