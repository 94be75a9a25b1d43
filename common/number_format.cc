#include "common/number_format.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <locale>
#include <sstream>

namespace common {

std::string format_shortest(double v) {
  if (!std::isfinite(v)) return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
  char buf[64];
  for (int p = 15; p <= 17; ++p) {
    std::snprintf(buf, sizeof buf, "%.*g", p, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

namespace {

// num_put facet: doubles through format_shortest, everything else as usual.
class ShortestDoublePut : public std::num_put<char> {
 protected:
  iter_type do_put(iter_type out, std::ios_base&, char_type, double v) const override {
    for (char c : format_shortest(v)) *out++ = c;
    return out;
  }
};

}  // namespace

void use_shortest_round_trip(std::ostream& out) {
  out.imbue(std::locale(out.getloc(), new ShortestDoublePut));
}

std::string format_fixed(double v, int digits) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << v;
  return o.str();
}

std::string format_significant(double v, int digits) {
  std::ostringstream o;
  o << std::setprecision(digits) << v;
  return o.str();
}

}  // namespace common
