// The library the loader loads. It opens the layer proper (libphyshand_layer_impl.so, beside
// it) with RTLD_DEEPBIND, so that the layer and the Bullet it links bind their symbols among
// themselves first: an app that exports a Bullet of its own (an engine linked with a copy
// of it) cannot capture the layer's calls into Bullet. It forwards the negotiation, through
// which the loader finds everything else in the layer proper.

#include <dlfcn.h>
#include <openxr/openxr.h>

#include <cstdio>
#include <string>

#include "loader_negotiation.h"

namespace {

constexpr const char* kImplementation = "libphyshand_layer_impl.so";

// The layer proper's negotiation, or null (said on stderr) when it cannot be loaded.
PFN_xrNegotiateLoaderApiLayerInterface open_layer() {
    Dl_info self{};
    if (dladdr(reinterpret_cast<const void*>(&open_layer), &self) == 0 ||
        self.dli_fname == nullptr) {
        std::fprintf(stderr, "physhand: cannot tell where the layer is; the layer is off\n");
        return nullptr;
    }
    std::string path = self.dli_fname;
    path = path.substr(0, path.rfind('/') + 1) + kImplementation;
    int mode = RTLD_NOW | RTLD_LOCAL;
#ifndef PHYSHAND_NO_DEEPBIND
    mode |= RTLD_DEEPBIND;  // AddressSanitizer refuses it: sanitizer builds go without
#endif
    // Never closed: the loader may call into the layer until the process ends.
    void* layer = dlopen(path.c_str(), mode);
    if (layer == nullptr) {
        std::fprintf(stderr, "physhand: %s; the layer is off\n", dlerror());
        return nullptr;
    }
    auto* negotiate = reinterpret_cast<PFN_xrNegotiateLoaderApiLayerInterface>(
        dlsym(layer, "xrNegotiateLoaderApiLayerInterface"));
    if (negotiate == nullptr) {
        std::fprintf(stderr, "physhand: %s has no negotiation; the layer is off\n", path.c_str());
    }
    return negotiate;
}

}  // namespace

extern "C" [[gnu::visibility("default")]] XRAPI_ATTR XrResult XRAPI_CALL
xrNegotiateLoaderApiLayerInterface(const XrNegotiateLoaderInfo* loaderInfo, const char* layerName,
                                   XrNegotiateApiLayerRequest* apiLayerRequest) {
    try {
        static const PFN_xrNegotiateLoaderApiLayerInterface negotiate = open_layer();
        if (negotiate == nullptr) return XR_ERROR_INITIALIZATION_FAILED;
        return negotiate(loaderInfo, layerName, apiLayerRequest);
    } catch (...) {
        // Out of memory finding the layer: nothing may escape into the loader.
        return XR_ERROR_INITIALIZATION_FAILED;
    }
}
