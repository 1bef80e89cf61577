#include "success_interval.h"

#include <algorithm>
#include <cmath>

SuccessInterval success_interval(int passed, int played, double z) {
    if (played <= 0) return {0.0, 1.0};
    const double n = played;
    const double share = std::clamp(passed / n, 0.0, 1.0);
    const double z2 = z * z;
    const double centre = (share + z2 / (2 * n)) / (1 + z2 / n);
    const double half = z / (1 + z2 / n) * std::sqrt(share * (1 - share) / n + z2 / (4 * n * n));
    // At none or all the bound is 0 or 1 exactly; rounding would leave it a hair off.
    return {passed <= 0 ? 0.0 : std::max(0.0, centre - half),
            passed >= played ? 1.0 : std::min(1.0, centre + half)};
}
