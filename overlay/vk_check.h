#pragma once

#include <vulkan/vulkan.h>

namespace physhand::overlay {

// Throws std::runtime_error naming the call (or what was missing) and the result code.
[[noreturn]] void throw_vulkan_error(const char* call, VkResult result);

inline void vk_check(VkResult result, const char* call) {
    if (result != VK_SUCCESS) {
        throw_vulkan_error(call, result);
    }
}

}  // namespace physhand::overlay

// A macro only to put the call's text in the message.
#define PHYSHAND_VK_CHECK(call) ::physhand::overlay::vk_check((call), #call)
