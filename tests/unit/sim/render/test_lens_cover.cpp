#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "sim/render/lens_cover.h"

namespace lineloc {
namespace {

// Covered from 10 s to 13 s.
TEST(LensCover, OpenFractionIsTheShareOfTheExposureOutsideTheWindow) {
  const LensCover cover(10.0, 3.0);
  EXPECT_EQ(cover.openFraction(5.0, 5.002), 1.0);
  EXPECT_EQ(cover.openFraction(11.0, 11.002), 0.0);
  EXPECT_EQ(cover.openFraction(13.0, 13.002), 1.0);  // the window's end is open
  EXPECT_EQ(cover.openFraction(9.998, 10.0), 1.0);
  // An exposure of 4 ms the cover's edges cut: 1 ms before it falls, 3 ms
  // after it lifts.
  EXPECT_NEAR(cover.openFraction(9.999, 10.003), 0.25, 1e-9);
  EXPECT_NEAR(cover.openFraction(12.999, 13.003), 0.75, 1e-9);
  // An exposure longer than the window: 4 s of 7 s open.
  EXPECT_NEAR(cover.openFraction(8.0, 15.0), 4.0 / 7.0, 1e-12);
}

TEST(LensCover, AnInstantIsOpenOrCovered) {
  const LensCover cover(10.0, 3.0);
  EXPECT_EQ(cover.openFraction(9.5, 9.5), 1.0);
  EXPECT_EQ(cover.openFraction(10.0, 10.0), 0.0);
  EXPECT_EQ(cover.openFraction(13.0, 13.0), 1.0);
  // A window of no length covers nothing.
  EXPECT_EQ(LensCover(10.0, 0.0).openFraction(10.0, 10.0), 1.0);
  EXPECT_EQ(LensCover(10.0, 0.0).openFraction(9.9, 10.1), 1.0);
}

TEST(LensCover, InvalidWindowsAndExposuresAreRefused) {
  EXPECT_THROW(LensCover(10.0, -1.0), std::invalid_argument);
  EXPECT_THROW(LensCover(std::numeric_limits<double>::quiet_NaN(), 1.0), std::invalid_argument);
  EXPECT_THROW(LensCover(0.0, std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_THROW(LensCover(10.0, 3.0).openFraction(11.0, 10.0), std::invalid_argument);
}

}  // namespace
}  // namespace lineloc
