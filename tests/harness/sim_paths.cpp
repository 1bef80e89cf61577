// Semantic paths: interned per instance; the atom is the 1-based index of the string.

#include <algorithm>

#include "sim_runtime.h"

namespace physhand::sim {
namespace {

// The well-formed path rules of the specification: "/a/b" of non-empty lower-case
// components, none of them "." or "..".
bool is_well_formed(std::string_view path) {
    if (path.size() < 2 || path.size() >= XR_MAX_PATH_LENGTH || path.front() != '/' ||
        path.back() == '/') {
        return false;
    }
    std::size_t start = 1;
    while (start <= path.size()) {
        std::size_t end = path.find('/', start);
        if (end == std::string_view::npos) end = path.size();
        std::string_view component = path.substr(start, end - start);
        if (component.empty() || component == "." || component == "..") return false;
        if (!std::all_of(component.begin(), component.end(), is_name_char)) return false;
        start = end + 1;
    }
    return true;
}

}  // namespace

bool path_exists(const InstanceData& instance, XrPath path) {
    return path != XR_NULL_PATH && path <= instance.paths.size();
}

XrResult xrStringToPath(XrInstance instance, const char* pathString, XrPath* path) {
    return guarded([&](Runtime& rt) {
        InstanceData* data = rt.instances.find(instance);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (pathString == nullptr || path == nullptr) return XR_ERROR_VALIDATION_FAILURE;
        if (!is_well_formed(pathString)) return XR_ERROR_PATH_FORMAT_INVALID;
        auto it = data->path_ids.find(std::string_view(pathString));
        if (it == data->path_ids.end()) {
            data->paths.emplace_back(pathString);
            it = data->path_ids.emplace(pathString, data->paths.size()).first;
        }
        *path = it->second;
        return XR_SUCCESS;
    });
}

XrResult xrPathToString(XrInstance instance, XrPath path, uint32_t bufferCapacityInput,
                        uint32_t* bufferCountOutput, char* buffer) {
    return guarded([&](Runtime& rt) {
        const InstanceData* data = rt.instances.find(instance);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!path_exists(*data, path)) return XR_ERROR_PATH_INVALID;
        const std::string& text = data->paths[path - 1];
        // The count includes the terminating null character.
        return fill_array(bufferCapacityInput, bufferCountOutput, buffer,
                          static_cast<uint32_t>(text.size() + 1), [&](char& out, uint32_t i) {
                              out = i < text.size() ? text[i] : '\0';
                              return XR_SUCCESS;
                          });
    });
}

}  // namespace physhand::sim
