#pragma once

// How sure a share of successes is: the Wilson score interval, at 95 % unless `z` says
// otherwise. 77 of 100 variants is 68-84 %; a family of 5 that all succeed, 57-100 %.
struct SuccessInterval {
    double low;   // 0..1
    double high;  // 0..1
};
SuccessInterval success_interval(int passed, int played, double z = 1.959964);
