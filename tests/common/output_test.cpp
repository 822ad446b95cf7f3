// The number formats of every CSV file (common/output.cpp): exactly what printf's "%.6f" and
// "%.9g" write, on values of every magnitude, since golden outputs are compared byte for byte.
#include "common/output.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>

namespace wsn::common {
namespace {

std::string printfFixed6(double value) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, "%.6f", value == 0.0 ? 0.0 : value);
  std::string text = buffer;
  return text == "-0.000000" ? "0.000000" : text;
}

std::string printfSignificant9(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.9g", value == 0.0 ? 0.0 : value);
  return buffer;
}

TEST_CASE("fixed6 and significant9 write what printf writes", "[output]") {
  const double cases[] = {0.0, -0.0, 1.0, -1.0, 0.5, 2.5, 1e-7, -4e-7, 5e-7, 0.0000005, 0.1234565, 1.0000005,
                          123456.7890125, 1e15, 1e17 + 3, 1e308, -1e308, 4.9e-324, 0.1, 2.0 / 3.0,
                          std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                          std::numeric_limits<double>::quiet_NaN()};
  for (const double value : cases) {
    CHECK(fixed6(value) == printfFixed6(value));
    CHECK(significant9(value) == printfSignificant9(value));
  }
  CHECK(fixed6(-0.0) == "0.000000");
  CHECK(fixed6(-1e-9) == "0.000000");
  CHECK(significant9(-0.0) == "0");
}

TEST_CASE("fixed6 and significant9 agree with printf on random doubles of every magnitude", "[output]") {
  std::mt19937_64 random(20261129);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-30, 30);
  for (int i = 0; i < 200000; ++i) {
    const double value = std::ldexp(mantissa(random), exponent(random));
    REQUIRE(fixed6(value) == printfFixed6(value));
    REQUIRE(significant9(value) == printfSignificant9(value));
  }
  // Exact ties at the sixth decimal: odd multiples of 1/128 = 0.0078125 end in a 5 at the
  // seventh, and round (to even) as printf rounds them.
  for (int k = 0; k < 4096; ++k) {
    const double value = (2 * k + 1) / 128.0;
    REQUIRE(fixed6(value) == printfFixed6(value));
  }
}

}  // namespace
}  // namespace wsn::common
