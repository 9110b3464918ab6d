// Shortest round-trip formatting of doubles (std::to_chars without a precision).
#include "particula/io/number.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

namespace particula::io {

void append_shortest(std::string& out, double v) {
  char buf[32];  // the longest shortest form, e.g. "-2.2250738585072014e-308", is 24 characters
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  if (ec == std::errc()) out.append(buf, end);
}

double round_significant(double v, int digits) {
  if (!std::isfinite(v) || digits < 1 || digits > 17) return v;
  char buf[40];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific, digits - 1);
  double r = v;
  if (ec == std::errc()) std::from_chars(buf, end, r);
  return r;
}

std::string shortest(double v) {
  std::string s;
  append_shortest(s, v);
  return s;
}

}  // namespace particula::io
