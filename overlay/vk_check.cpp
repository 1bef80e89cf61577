#include "vk_check.h"

#include <stdexcept>
#include <string>

namespace physhand::overlay {

void throw_vulkan_error(const char* call, VkResult result) {
    throw std::runtime_error(std::string("overlay renderer: ") + call + " failed with VkResult " +
                             std::to_string(result));
}

}  // namespace physhand::overlay
