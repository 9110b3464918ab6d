// Numbers as text in every output file (CSV, JSON, the .pvd index): the shortest decimal that
// reads back to exactly the same double (std::to_chars, round-trip), so 0.35 is written "0.35"
// and a row can be selected by the time it shows.
#pragma once

#include <string>

namespace particula::io {

/// Appends the shortest text that reads back as exactly `v` ("0.35", "1e-05", "2", "-0.5").
/// Non-finite values are written "inf", "-inf" or "nan" (callers that must not write them check first).
void append_shortest(std::string& out, double v);

/// The shortest round-trip text of `v` (see append_shortest).
std::string shortest(double v);

/// The double nearest to `v` rounded to `digits` significant decimal digits (1 to 17): 7 * 0.05
/// = 0.35000000000000003 becomes 0.35. Non-finite values are returned unchanged.
double round_significant(double v, int digits = 15);

}  // namespace particula::io
