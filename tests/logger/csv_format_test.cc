#include "logger/csv_format.h"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

namespace mrsim {
namespace {

std::string ToChars(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, r.ptr);
}

std::string Ours(double v) {
  std::string s;
  AppendDouble(v, &s);
  return s;
}

// The CSV's numbers must stay exactly what std::to_chars writes (shortest
// round trip, its choice of fixed or scientific), so old and new logs and
// live and replayed runs compare byte for byte.
TEST(CsvFormat, DoublesAreWrittenExactlyAsToCharsWrites) {
  for (double v : {0.0,
                   -0.0,
                   1.0,
                   -1.0,
                   0.1,
                   0.30000000000000004,
                   1e-300,
                   1e300,
                   5e-324,
                   std::numeric_limits<double>::max(),
                   std::numeric_limits<double>::min(),
                   123456789012345680.0,
                   1e16,
                   1e15,
                   1e22,
                   1e23,
                   0.0001,
                   0.00001,
                   1e-5,
                   12345.678,
                   100.0,
                   1234567.0,
                   9.5367431640625e-07,
                   2.0 / 3.0,
                   std::numeric_limits<double>::infinity(),
                   -std::numeric_limits<double>::infinity(),
                   std::numeric_limits<double>::quiet_NaN()}) {
    EXPECT_EQ(Ours(v), ToChars(v)) << ToChars(v);
  }
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> uniform(-10.0, 10.0);
  std::uniform_int_distribution<int> decimals(0, 6);
  for (int i = 0; i < 2000000; ++i) {
    double v;
    switch (i % 4) {
      case 0: {  // any bit pattern: every exponent
        const std::uint64_t bits = random();
        std::memcpy(&v, &bits, sizeof v);
        if (!std::isfinite(v)) continue;
        break;
      }
      case 1:  // values like a simulation's
        v = uniform(random);
        break;
      case 2:  // short decimals (0.25, 1.5e-3), where fixed and scientific
               // lengths are close
        v = std::round(uniform(random) * 1000) /
            std::pow(10.0, decimals(random));
        break;
      default:  // integers and powers of ten around the switch-over
        v = std::pow(10.0, static_cast<int>(random() % 40) - 20) *
            static_cast<double>(random() % 1000);
        break;
    }
    const std::string expected = ToChars(v);
    const std::string got = Ours(v);
    if (got != expected) {
      ADD_FAILURE() << "value " << expected << " written as " << got;
      break;
    }
  }
}

TEST(CsvFormat, TextWithCommasOrQuotesIsQuoted) {
  std::string s;
  AppendCsvText("plain", &s);
  s += ',';
  AppendCsvText("a,\"b\"", &s);
  EXPECT_EQ(s, "plain,\"a,\"\"b\"\"\"");
}

}  // namespace
}  // namespace mrsim
