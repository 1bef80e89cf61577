#pragma once

#include <openxr/openxr.h>

#include <array>
#include <filesystem>
#include <memory>

// An application on the simulated runtime, through the real OpenXR loader and the layer
// manifests of the build tree: one instance with one running session, headless or Vulkan,
// with or without the physhand layer. For the tools that fuzz or time the layer from the
// app's side.
namespace physhand::test {

class AppVulkan;

// A zeroed OpenXR structure carrying its type tag.
template <typename T>
T xr(XrStructureType type) {
    T s{};
    s.type = type;
    return s;
}

// Throws std::runtime_error naming `call` when `result` is a failure.
void check(XrResult result, const char* call);

struct SimAppOptions {
    bool layer = true;            // false: the implicit layer is disabled, as a user would do it
    bool extension = false;       // enable XR_PHYSHAND_physical_hands (only the layer provides it)
    std::filesystem::path scene;  // the scene whose hands the runtime plays
    std::filesystem::path config{};  // the layer's config file; empty: none (its defaults)
    // A Vulkan session (XR_KHR_vulkan_enable2) that shows a projection layer each frame, on
    // the system's Vulkan device (lavapipe where VK_ICD_FILENAMES says so); else headless.
    bool vulkan = false;
};

class SimApp {
  public:
    // Sets the environment the loader, the layer and the runtime read at instance creation,
    // then creates the instance, a running session, reference spaces and both hand trackers.
    // Throws std::runtime_error naming the call that failed.
    explicit SimApp(const SimAppOptions& options);
    ~SimApp();
    SimApp(const SimApp&) = delete;
    SimApp& operator=(const SimApp&) = delete;

    // xrGetInstanceProcAddr; throws std::runtime_error when the function is not available.
    template <typename Pfn>
    Pfn function(const char* name) const {
        return reinterpret_cast<Pfn>(void_function(name));
    }

    XrInstance instance() const { return instance_.handle; }
    XrSession session() const { return session_; }
    // VIEW, LOCAL or STAGE, with an identity pose.
    XrSpace space(XrReferenceSpaceType type) const;
    XrHandTrackerEXT hand_tracker(XrHandEXT hand) const;

    // One whole frame (wait, begin, end: no layers when headless, a projection layer of an
    // acquired and released swapchain image in a Vulkan session); its predicted display time
    // and period.
    XrFrameState frame() const;

  private:
    // Destroys the instance (and with it everything below) also when the constructor throws.
    struct Instance {
        XrInstance handle = XR_NULL_HANDLE;
        ~Instance();
    };

    PFN_xrVoidFunction void_function(const char* name) const;

    // Before instance_, so that the device outlives the session that uses it.
    std::unique_ptr<AppVulkan> vulkan_;
    Instance instance_;
    XrSession session_ = XR_NULL_HANDLE;
    std::array<XrSpace, 3> spaces_{};                  // VIEW, LOCAL, STAGE (enum values 1..3)
    std::array<XrHandTrackerEXT, 2> hand_trackers_{};  // left, right (enum values 1..2)
};

}  // namespace physhand::test
