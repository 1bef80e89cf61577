#include "success_interval.h"

#include <gtest/gtest.h>

TEST(SuccessInterval, OfAHundredVariants) {
    const SuccessInterval i = success_interval(77, 100);
    EXPECT_NEAR(i.low, 0.6785, 1e-4);
    EXPECT_NEAR(i.high, 0.8416, 1e-4);
}

TEST(SuccessInterval, AllOrNoneOfAFewStillLeaveRoom) {
    const SuccessInterval all = success_interval(5, 5);
    EXPECT_NEAR(all.low, 0.5655, 1e-4);
    EXPECT_DOUBLE_EQ(all.high, 1.0);
    const SuccessInterval none = success_interval(0, 5);
    EXPECT_DOUBLE_EQ(none.low, 0.0);
    EXPECT_NEAR(none.high, 0.4345, 1e-4);
}

TEST(SuccessInterval, NarrowsAsMoreArePlayed) {
    const SuccessInterval few = success_interval(8, 10);
    const SuccessInterval many = success_interval(80, 100);
    EXPECT_LT(many.high - many.low, few.high - few.low);
    EXPECT_LT(few.low, 0.8);
    EXPECT_GT(few.high, 0.8);
}

TEST(SuccessInterval, NothingPlayedSaysNothing) {
    const SuccessInterval i = success_interval(0, 0);
    EXPECT_DOUBLE_EQ(i.low, 0.0);
    EXPECT_DOUBLE_EQ(i.high, 1.0);
}
