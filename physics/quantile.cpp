#include "quantile.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace physhand {

double quantile(std::vector<double> values, double q) {
    if (values.empty()) return 0.0;
    const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size()))) -
                   (q > 0 ? 1 : 0);
    const auto nth = values.begin() + static_cast<std::ptrdiff_t>(std::min(k, values.size() - 1));
    std::nth_element(values.begin(), nth, values.end());
    return *nth;
}

}  // namespace physhand
