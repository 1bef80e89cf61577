#pragma once

#include <stdexcept>

namespace physhand {

// A file that does not conform; what() names the JSON path and what was expected,
// e.g. "colliders[2].half_extents: expected an array of 3 numbers".
class FormatError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace physhand
