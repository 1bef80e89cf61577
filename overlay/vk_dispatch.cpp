#include "vk_dispatch.h"

#include <string>

#include "vk_check.h"

namespace physhand::overlay {

namespace {

template <typename Function>
Function require(PFN_vkVoidFunction function, const char* name) {
    if (function == nullptr) {
        throw_vulkan_error((std::string("loading ") + name).c_str(),
                           VK_ERROR_INITIALIZATION_FAILED);
    }
    return reinterpret_cast<Function>(function);
}

}  // namespace

VulkanFunctions load_vulkan_functions(VkInstance instance,
                                      PFN_vkGetInstanceProcAddr get_instance_proc_addr,
                                      VkDevice device) {
    VulkanFunctions vk;
    if (instance == VK_NULL_HANDLE) {
#define PHYSHAND_VK_LOAD_EXPORTED(name) vk.name = &::name;
        PHYSHAND_VK_INSTANCE_FUNCTIONS(PHYSHAND_VK_LOAD_EXPORTED)
#undef PHYSHAND_VK_LOAD_EXPORTED
    } else {
        const PFN_vkGetInstanceProcAddr gipa =
            get_instance_proc_addr != nullptr ? get_instance_proc_addr : &::vkGetInstanceProcAddr;
#define PHYSHAND_VK_LOAD_INSTANCE(name) vk.name = require<PFN_##name>(gipa(instance, #name), #name);
        PHYSHAND_VK_INSTANCE_FUNCTIONS(PHYSHAND_VK_LOAD_INSTANCE)
#undef PHYSHAND_VK_LOAD_INSTANCE
    }
#define PHYSHAND_VK_LOAD_DEVICE(name) \
    vk.name = require<PFN_##name>(vk.vkGetDeviceProcAddr(device, #name), #name);
    PHYSHAND_VK_DEVICE_FUNCTIONS(PHYSHAND_VK_LOAD_DEVICE)
#undef PHYSHAND_VK_LOAD_DEVICE
    return vk;
}

}  // namespace physhand::overlay
