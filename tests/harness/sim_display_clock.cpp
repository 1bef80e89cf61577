// The virtual display's timing: its rate, each frame's jitter and the frames it drops, or
// no frame loop at all, and the XR_KHR_convert_timespec_time clock.

#include "sim_runtime.h"

namespace physhand::sim {

DisplayClock DisplayClock::from_environment() {
    DisplayClock clock;
    if (const std::optional<double> rate =
            decimal_env("PHYSHAND_SIM_DISPLAY_HZ", kMinDisplayHz, kMaxDisplayHz)) {
        clock.period_ns = frame_period_ns(*rate);
    }
    const double max_jitter_ms = max_frame_jitter_ms(1e9 / static_cast<double>(clock.period_ns));
    if (const std::optional<double> jitter =
            decimal_env("PHYSHAND_SIM_FRAME_JITTER_MS", 0.0, max_jitter_ms)) {
        clock.jitter_ns = std::llround(*jitter * 1e6);
    }
    clock.jitter_seed = static_cast<std::uint64_t>(
        whole_number_env("PHYSHAND_SIM_FRAME_JITTER_SEED", 0).value_or(0));
    clock.drop_every = whole_number_env("PHYSHAND_SIM_DROP_EVERY", 2).value_or(0);
    if (const std::optional<std::int64_t> loop =
            whole_number_env("PHYSHAND_SIM_HEADLESS_FRAME_LOOP", 0)) {
        clock.headless_frame_loop = *loop != 0;
    }
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    clock.monotonic_origin_ns = now.tv_sec * 1'000'000'000LL + now.tv_nsec;
    return clock;
}

XrTime DisplayClock::display_time(std::int64_t waited) const {
    const std::int64_t slot = drop_every == 0 ? waited : waited + waited / (drop_every - 1);
    return kSceneStart + (slot + 1) * period_ns + frame_jitter_ns(slot + 1, jitter_ns, jitter_seed);
}

XrResult xrConvertTimespecTimeToTimeKHR(XrInstance instance, const timespec* timespecTime,
                                        XrTime* time) {
    return guarded([&](Runtime& rt) {
        const InstanceData* data = rt.instances.find(instance);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!data->convert_timespec) return XR_ERROR_FUNCTION_UNSUPPORTED;
        if (timespecTime == nullptr || time == nullptr || timespecTime->tv_nsec < 0 ||
            timespecTime->tv_nsec >= 1'000'000'000) {
            return XR_ERROR_VALIDATION_FAILURE;
        }
        const XrTime converted = data->display.from_monotonic(
            timespecTime->tv_sec * 1'000'000'000LL + timespecTime->tv_nsec);
        if (converted <= 0) return XR_ERROR_TIME_INVALID;
        *time = converted;
        return XR_SUCCESS;
    });
}

XrResult xrConvertTimeToTimespecTimeKHR(XrInstance instance, XrTime time, timespec* timespecTime) {
    return guarded([&](Runtime& rt) {
        const InstanceData* data = rt.instances.find(instance);
        if (data == nullptr) return XR_ERROR_HANDLE_INVALID;
        if (!data->convert_timespec) return XR_ERROR_FUNCTION_UNSUPPORTED;
        if (timespecTime == nullptr) return XR_ERROR_VALIDATION_FAILURE;
        const std::int64_t ns = data->display.to_monotonic(time);
        if (time <= 0 || ns < 0) return XR_ERROR_TIME_INVALID;
        timespecTime->tv_sec = ns / 1'000'000'000LL;
        timespecTime->tv_nsec = ns % 1'000'000'000LL;
        return XR_SUCCESS;
    });
}

std::int64_t DisplayClock::frame_slot(XrTime display_time) const {
    const double periods =
        static_cast<double>(display_time - kSceneStart) / static_cast<double>(period_ns);
    return std::max<std::int64_t>(std::llround(periods), 0);
}

}  // namespace physhand::sim
