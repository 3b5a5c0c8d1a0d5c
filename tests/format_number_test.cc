// base/format_number.h writes the bytes an ostream with precision(p) writes ("%.pg"): checked
// on values that take every branch of %g (fixed and exponent form, trailing zeros dropped,
// negative zero, subnormals, the largest double) and on 100,000 random doubles of every
// exponent, at the two precisions the writers use (12 for fields, 17 for mesh points).
#include "base/format_number.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <sstream>

namespace pqlayout {
namespace {

std::string Streamed(double x, int precision) {
  std::ostringstream s;
  s.precision(precision);
  s << x;
  return s.str();
}

std::string Formatted(double x, int precision) {
  std::string s;
  AppendNumber(&s, x, precision);
  return s;
}

TEST(FormatNumber, SameBytesAsTheStreamOnEveryBranchOfG) {
  const double values[] = {0.0, -0.0, 1.0, -1.0, 0.1, 1.0 / 3.0, 2.5e-5, 1e-4, 123456789012.0, 1234567890123.0,
                           1e17, 1.5e300, 5e-324, std::numeric_limits<double>::max(), -7.25, 100.0, 1e16};
  for (const int precision : {12, 17})
    for (const double x : values) EXPECT_EQ(Formatted(x, precision), Streamed(x, precision)) << x;
  EXPECT_EQ(Formatted(0.1, 17), "0.10000000000000001");  // the known answer, not just agreement
  EXPECT_EQ(Formatted(-0.0, 12), "-0");
  EXPECT_EQ(Formatted(1e-5, 12), "1e-05");
}

TEST(FormatNumber, SameBytesAsTheStreamOnRandomDoubles) {
  std::mt19937_64 random(7);
  int checked = 0;
  for (int i = 0; i < 100000; ++i) {
    const std::uint64_t bits = random();
    double x;
    std::memcpy(&x, &bits, sizeof x);
    if (!std::isfinite(x)) continue;
    ++checked;
    for (const int precision : {12, 17}) ASSERT_EQ(Formatted(x, precision), Streamed(x, precision)) << precision;
  }
  EXPECT_GT(checked, 99000);
  std::ostringstream out;
  WriteNumber(out, 2.0 / 3.0, 12);
  EXPECT_EQ(out.str(), "0.666666666667");
}

// Messages: three significant digits, whole numbers from 1e3 below 1e12 (map coordinates of
// either sign), the exponent form outside.
TEST(FormatNumber, ReadableNumbersForMessages) {
  EXPECT_EQ(ReadableNumber(0.015), "0.015");
  EXPECT_EQ(ReadableNumber(2.71828), "2.72");
  EXPECT_EQ(ReadableNumber(999.4), "999");
  EXPECT_EQ(ReadableNumber(6180.4), "6180");
  EXPECT_EQ(ReadableNumber(-5431234.6), "-5431235");
  EXPECT_EQ(ReadableNumber(999999999999.0), "999999999999");
  EXPECT_EQ(ReadableNumber(2.75e13), "2.75e+13");
  EXPECT_EQ(ReadableNumber(1e-7), "1e-07");
}

}  // namespace
}  // namespace pqlayout
