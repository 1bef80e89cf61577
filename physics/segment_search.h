#pragma once

#include <LinearMath/btScalar.h>

namespace physhand {

// Where along a segment, as a fraction t of it, a function convex in t (a distance to a convex
// set) is least: 24 golden-section steps narrow it to 1e-5 of the segment (a flat stretch of
// minima: somewhere in it).
template <class Convex>
btScalar least_along_segment(const Convex& f) {
    constexpr btScalar kShrink = 0.6180340f;
    constexpr int kSteps = 24;
    btScalar lo = 0, hi = 1;
    btScalar x1 = hi - kShrink, x2 = lo + kShrink;
    btScalar f1 = f(x1), f2 = f(x2);
    for (int i = 0; i < kSteps; ++i) {
        if (f1 <= f2) {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - kShrink * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + kShrink * (hi - lo);
            f2 = f(x2);
        }
    }
    return (lo + hi) / 2;
}

}  // namespace physhand
