#pragma once

// A Vulkan device with no window for the overlay tests and benchmark: instance (with the
// Khronos validation layer when installed and wanted), the first device with a graphics
// queue, offscreen images, and pixel readback.

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace physhand::overlay::testing {

// Validation messages (warnings and errors), from any thread.
class ValidationMessages {
  public:
    void add(std::string message);
    std::vector<std::string> take();

  private:
    std::mutex mutex_;
    std::vector<std::string> messages_;
};

struct Rgba {
    int r = 0, g = 0, b = 0, a = 0;
};

// 8-bit RGBA pixels of one image layer, rows top to bottom.
struct Pixels {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> bytes;

    Rgba at(uint32_t x, uint32_t y) const;
    bool operator==(const Pixels&) const = default;
};

struct OffscreenImage {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{};
    uint32_t layers = 1;
};

class HeadlessVulkan {
  public:
    // Null, with the reason, when no instance or device can be created. With
    // `validation`, messages go to `messages`, which must outlive the HeadlessVulkan.
    static std::unique_ptr<HeadlessVulkan> create(bool validation, ValidationMessages* messages,
                                                  std::string& reason);
    ~HeadlessVulkan();
    HeadlessVulkan(const HeadlessVulkan&) = delete;
    HeadlessVulkan& operator=(const HeadlessVulkan&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physical_device() const { return physical_device_; }
    VkDevice device() const { return device_; }
    uint32_t queue_family() const { return queue_family_; }
    VkQueue queue() const { return queue_; }
    bool validating() const { return messenger_ != VK_NULL_HANDLE; }
    std::string device_name() const;

    // Colour-attachment and transfer usage, like a swapchain image plus readback.
    OffscreenImage create_image(VkFormat format, VkExtent2D extent, uint32_t layers);
    void destroy_image(OffscreenImage& image);
    // Clears every layer to `color` (linear floats) and leaves the image in `layout`.
    void fill(const OffscreenImage& image, std::array<float, 4> color, VkImageLayout layout);
    // Reads one layer of an image that is, and stays, in `layout`.
    Pixels read(const OffscreenImage& image, uint32_t layer, VkImageLayout layout);

  private:
    HeadlessVulkan() = default;
    // Records with `record` into a one-time command buffer, submits it, waits for it.
    template <typename Record>
    void run_once(Record record);

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    uint32_t queue_family_ = 0;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkCommandPool command_pool_ = VK_NULL_HANDLE;
};

}  // namespace physhand::overlay::testing
