// Contact sheets: a session's story in one image, for a person to look at, so tiles are
// smaller than the views, yet large enough for a few centimetres at a table to read, and
// picked evenly over the captured frames.

#include <algorithm>
#include <cstdint>

#include "sim_runtime.h"

namespace physhand::sim {
namespace {

constexpr std::uint32_t kShrink = 2;  // a tile is half a view's width and height
constexpr std::size_t kTiles = 6;     // at most, in rows of kColumns
constexpr std::uint32_t kColumns = 3;
constexpr std::uint32_t kGap = 4;  // black pixels between tiles

}  // namespace

// The mean of each kShrink x kShrink block, taken on the sRGB codes: a contact sheet is
// looked at, not measured.
Rgba8Image sheet_tile(const Rgba8Image& view) {
    Rgba8Image tile{view.width / kShrink, view.height / kShrink, {}};
    tile.pixels.resize(std::size_t{4} * tile.width * tile.height);
    for (std::uint32_t y = 0; y < tile.height; ++y) {
        for (std::uint32_t x = 0; x < tile.width; ++x) {
            for (std::size_t c = 0; c < 4; ++c) {
                std::uint32_t sum = 0;
                for (std::uint32_t dy = 0; dy < kShrink; ++dy) {
                    for (std::uint32_t dx = 0; dx < kShrink; ++dx) {
                        const std::size_t i =
                            std::size_t{view.width} * (y * kShrink + dy) + x * kShrink + dx;
                        sum += view.pixels[4 * i + c];
                    }
                }
                tile.pixels[4 * (std::size_t{tile.width} * y + x) + c] =
                    static_cast<std::uint8_t>(sum / (kShrink * kShrink));
            }
        }
    }
    return tile;
}

Rgba8Image contact_sheet(const std::vector<Rgba8Image>& tiles) {
    const std::size_t count = std::min(tiles.size(), kTiles);
    if (count == 0) return {};
    const std::uint32_t width = tiles[0].width, height = tiles[0].height;
    const auto columns = std::min<std::uint32_t>(kColumns, static_cast<std::uint32_t>(count));
    const auto rows = static_cast<std::uint32_t>((count + columns - 1) / columns);
    Rgba8Image sheet{columns * width + (columns - 1) * kGap, rows * height + (rows - 1) * kGap, {}};
    sheet.pixels.assign(std::size_t{4} * sheet.width * sheet.height, 0);
    for (std::size_t i = 0; i < sheet.pixels.size(); i += 4) sheet.pixels[i + 3] = 255;
    for (std::size_t k = 0; k < count; ++k) {
        // Evenly spaced from the first tile to the last.
        const std::size_t pick = count == 1 ? 0 : k * (tiles.size() - 1) / (count - 1);
        const Rgba8Image& tile = tiles[pick];
        const std::uint32_t left = static_cast<std::uint32_t>(k % columns) * (width + kGap);
        const std::uint32_t top = static_cast<std::uint32_t>(k / columns) * (height + kGap);
        for (std::uint32_t y = 0; y < std::min(height, tile.height); ++y) {
            std::copy_n(tile.pixels.begin() + std::ptrdiff_t{4} * tile.width * y,
                        std::size_t{4} * std::min(width, tile.width),
                        sheet.pixels.begin() +
                            std::ptrdiff_t{4} * (std::size_t{sheet.width} * (top + y) + left));
        }
    }
    return sheet;
}

}  // namespace physhand::sim
