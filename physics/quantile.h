#pragma once

#include <vector>

namespace physhand {

// Value at quantile q (0..1) by nearest rank; 0 for an empty set.
double quantile(std::vector<double> values, double q);

}  // namespace physhand
