// io: shortest round-trip text of doubles, and rounding to significant digits (output times).
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <limits>

#include "particula/io/number.hpp"

using namespace particula::io;

TEST(Number, ShortestIsExactAndShort) {
  EXPECT_EQ(shortest(0.35), "0.35");
  EXPECT_EQ(shortest(7 * 0.05), "0.35000000000000003");  // another double: written as it is
  EXPECT_EQ(shortest(1.0), "1");
  EXPECT_EQ(shortest(-2.5e-7), "-2.5e-07");
  for (const double v : {1.0 / 3.0, 0.1 + 0.2, 6.02214076e23, 5e-324, std::numeric_limits<double>::max()}) {
    const std::string s = shortest(v);
    double back = 0;
    std::from_chars(s.data(), s.data() + s.size(), back);
    EXPECT_EQ(back, v) << s;
  }
  std::string out = "t=";
  append_shortest(out, 0.125);
  EXPECT_EQ(out, "t=0.125");
}

TEST(Number, RoundSignificantGivesTheDecimalAnOutputTimeStandsFor) {
  EXPECT_EQ(round_significant(7 * 0.05), 0.35);
  EXPECT_EQ(round_significant(35 * 0.0025), 0.0875);
  EXPECT_EQ(round_significant(3 * 0.1), 0.3);
  EXPECT_EQ(round_significant(1.0 / 3.0), 0.333333333333333);
  EXPECT_EQ(round_significant(1.0 / 3.0, 17), 1.0 / 3.0);
  EXPECT_EQ(round_significant(12345.678, 3), 12300.0);
  EXPECT_TRUE(std::isinf(round_significant(std::numeric_limits<double>::infinity())));
  EXPECT_EQ(round_significant(0.0), 0.0);
}
