// Frame capture: with PHYSHAND_SIM_CAPTURE=DIR, composited frames of Vulkan sessions are
// written to DIR/frame_NNNNN_viewV.png, NNNNN the scene frame the frame is displayed at,
// and with PHYSHAND_SIM_CONTACT_SHEET=FILE also tiled into one contact sheet.
// Reading images back costs a queue round trip and CPU blending, so without capture
// nothing is read back, and with it only the frames written: every
// PHYSHAND_SIM_CAPTURE_EVERY-th (30 by default; 1 for all) and the last one. Failures are
// reported on stderr, never to the application: capture only observes.

#include <png.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <system_error>

#include "sim_runtime.h"

namespace physhand::sim {
namespace {

constexpr std::int64_t kDefaultEvery = 30;

}  // namespace

void write_png(const std::filesystem::path& path, const Rgba8Image& image) {
    FILE* file = std::fopen(path.c_str(), "wb");
    if (file == nullptr) {
        std::fprintf(stderr, "physhand simulated runtime: cannot write %s\n", path.c_str());
        return;
    }
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png == nullptr ? nullptr : png_create_info_struct(png);
    // libpng reports errors by longjmp, so nothing here may need a destructor.
    if (info != nullptr && setjmp(png_jmpbuf(png)) == 0) {
        png_init_io(png, file);
        png_set_IHDR(png, info, image.width, image.height, 8, PNG_COLOR_TYPE_RGBA,
                     PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
        // Fast rather than small: frames are many and looked at once.
        png_set_compression_level(png, 1);
        png_write_info(png, info);
        for (std::uint32_t y = 0; y < image.height; ++y) {
            png_write_row(png, image.pixels.data() + std::size_t{4} * image.width * y);
        }
        png_write_end(png, nullptr);
    } else {
        std::fprintf(stderr, "physhand simulated runtime: cannot encode %s\n", path.c_str());
    }
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
}

std::optional<CaptureSettings> capture_settings() {
    const char* dir = std::getenv("PHYSHAND_SIM_CAPTURE");
    if (dir == nullptr || *dir == '\0') return std::nullopt;
    CaptureSettings settings{
        dir, whole_number_env("PHYSHAND_SIM_CAPTURE_EVERY", 1).value_or(kDefaultEvery), {}};
    if (const char* sheet = std::getenv("PHYSHAND_SIM_CONTACT_SHEET"))
        settings.contact_sheet = sheet;
    std::error_code error;
    std::filesystem::create_directories(settings.dir, error);
    if (error) {
        std::fprintf(stderr, "physhand simulated runtime: cannot create %s (%s); no capture\n", dir,
                     error.message().c_str());
        return std::nullopt;
    }
    return settings;
}

void capture_frame(Runtime& rt, XrSession session, const XrFrameEndInfo& info) {
    SessionData& data = *rt.sessions.find(session);
    const InstanceData& instance = *rt.instances.find(data.instance);
    // A headless session has no images to show.
    if (!instance.capture || !data.vulkan) return;
    // The last frame: the first one ended after the session began to stop, whether at the
    // end of the scene or on request.
    bool last = data.stop_queued && !data.last_frame_captured;
    const std::int64_t frame = instance.display.frame_slot(info.displayTime);
    if (frame % instance.capture->every != 0 && !last) return;
    data.last_frame_captured |= last;
    std::vector<Rgba8Image> views;
    try {
        views = compose_layers(rt, session, info);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "physhand simulated runtime: frame %lld not captured: %s\n",
                     static_cast<long long>(frame), e.what());
        return;
    }
    for (std::size_t v = 0; v < views.size(); ++v) {
        char name[64];
        std::snprintf(name, sizeof(name), "frame_%05lld_view%zu.png", static_cast<long long>(frame),
                      v);
        write_png(instance.capture->dir / name, views[v]);
    }
    if (instance.capture->contact_sheet.empty() || views.empty()) return;
    data.sheet_tiles.push_back(sheet_tile(views[0]));
}

}  // namespace physhand::sim
