#include "png_file.h"

#include <png.h>

#include <stdexcept>
#include <string>

namespace physhand::test {

PngImage read_png(const std::filesystem::path& path) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&image, path.c_str())) {
        throw std::runtime_error("cannot read " + path.string() + ": " + image.message);
    }
    image.format = PNG_FORMAT_RGBA;
    PngImage png;
    png.width = image.width;
    png.height = image.height;
    png.pixels.resize(PNG_IMAGE_SIZE(image));
    if (!png_image_finish_read(&image, nullptr, png.pixels.data(), 0, nullptr)) {
        throw std::runtime_error("cannot decode " + path.string() + ": " + image.message);
    }
    return png;
}

}  // namespace physhand::test
