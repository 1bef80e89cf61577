#pragma once

// Reading a captured PNG back in a test: the simulated runtime's frames, checked by pixel.

#include <gtest/gtest.h>
#include <png.h>

#include <cstdint>
#include <filesystem>
#include <vector>

namespace physhand::test {

struct Rgba {
    int r, g, b, a;
};

struct Png {
    png_uint_32 width = 0, height = 0;
    std::vector<std::uint8_t> pixels;  // RGBA
    Rgba at(png_uint_32 x, png_uint_32 y) const {
        const std::uint8_t* p = &pixels[4 * (std::size_t(y) * width + x)];
        return {p[0], p[1], p[2], p[3]};
    }
};

inline Png read_png(const std::filesystem::path& path) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    Png png;
    if (!png_image_begin_read_from_file(&image, path.c_str())) {
        ADD_FAILURE() << "cannot read " << path << ": " << image.message;
        return png;
    }
    image.format = PNG_FORMAT_RGBA;
    png.width = image.width;
    png.height = image.height;
    png.pixels.resize(PNG_IMAGE_SIZE(image));
    EXPECT_TRUE(png_image_finish_read(&image, nullptr, png.pixels.data(), 0, nullptr));
    return png;
}

}  // namespace physhand::test
