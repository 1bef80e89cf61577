// Checks a frame hello_xr showed through the layer (run_hello_xr.sh passes it the last
// captured view): hello_xr's cubes are there, and the overlay's right hand is drawn around
// where the scene's right wrist projects, and nowhere else.
//
// Usage: hello_xr_capture_check U V PNG
//   U, V: where the wrist projects in the image, in [0, 1] from the top left.
// Exit status 0 when the frame passes, 1 (with the counts on stderr) when not, 2 when the
// check cannot run.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>

#include "png_file.h"

namespace {

using physhand::test::PngImage;

// hello_xr draws its cubes unlit, faces of pure primaries (a channel at 0); the overlay's
// right hand is green (overlay::Settings), shaded and blended, never with a channel at 0.
bool is_cube(const std::uint8_t* p) {
    return std::min({p[0], p[1], p[2]}) == 0 && std::max({p[0], p[1], p[2]}) >= 100;
}
bool is_right_hand(const std::uint8_t* p) {
    return std::min({p[0], p[1], p[2]}) > 0 && p[1] > p[0] + 60 && p[1] > p[2] + 60;
}

struct Counts {
    long hand_near = 0;  // hand pixels within reach of the wrist
    long hand_far = 0;   // hand pixels beyond it
    long cube = 0;
};

Counts count(const PngImage& png, double u, double v) {
    // The hand spans about 0.1 of the image around its wrist at the scene's distance.
    const double reach = png.width / 6.0;
    const double cx = u * png.width, cy = v * png.height;
    Counts counts;
    for (std::uint32_t y = 0; y < png.height; ++y) {
        for (std::uint32_t x = 0; x < png.width; ++x) {
            const std::uint8_t* p = png.at(x, y);
            if (is_cube(p)) ++counts.cube;
            if (!is_right_hand(p)) continue;
            const bool near = std::hypot(x + 0.5 - cx, y + 0.5 - cy) <= reach;
            ++(near ? counts.hand_near : counts.hand_far);
        }
    }
    return counts;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: hello_xr_capture_check U V PNG\n");
        return 2;
    }
    try {
        const PngImage png = physhand::test::read_png(argv[3]);
        const Counts counts = count(png, std::stod(argv[1]), std::stod(argv[2]));
        const long pixels = static_cast<long>(png.width) * png.height;
        // A few cubes of hello_xr's fill well over 0.5 % of the view, the hand over 0.1 %.
        const bool cubes = counts.cube > pixels / 200;
        const bool hand = counts.hand_near > pixels / 1000 && counts.hand_far == 0;
        std::fprintf(stderr,
                     "hello_xr_capture_check: %s: %ld cube pixels, %ld hand pixels near the "
                     "wrist, %ld elsewhere, of %ld\n",
                     argv[3], counts.cube, counts.hand_near, counts.hand_far, pixels);
        if (!cubes) std::fprintf(stderr, "hello_xr_capture_check: hello_xr's cubes are missing\n");
        if (!hand) {
            std::fprintf(stderr,
                         "hello_xr_capture_check: the hand is not drawn where the scene's "
                         "wrist projects\n");
        }
        return cubes && hand ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "hello_xr_capture_check: %s\n", e.what());
        return 2;
    }
}
