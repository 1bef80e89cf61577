#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

// Reading the simulated runtime's PNG captures back, for the checks of what it composited.
namespace physhand::test {

struct Rgba {
    int r, g, b, a;
};

struct PngImage {
    std::uint32_t width = 0, height = 0;
    std::vector<std::uint8_t> pixels;  // RGBA, 8 bits a channel, rows top to bottom
    const std::uint8_t* at(std::uint32_t x, std::uint32_t y) const {
        return &pixels[4 * (std::size_t(y) * width + x)];
    }
    Rgba rgba(std::uint32_t x, std::uint32_t y) const {
        const std::uint8_t* p = at(x, y);
        return {p[0], p[1], p[2], p[3]};
    }
};

// Throws std::runtime_error naming the file when it cannot be read as a PNG.
PngImage read_png(const std::filesystem::path& path);

}  // namespace physhand::test
