#pragma once
/// @file number_format.h
/// Numbers as text for files and messages that people and programs read back: the shortest
/// text that reads back as the same double (labels, command lines, summaries), and fixed
/// decimals (timings, percentages), a few significant digits (report tables).

#include <ostream>
#include <string>

namespace common {

/// Shortest printf-%g text (15 to 17 significant digits) that strtod reads back as exactly
/// `v`; "nan", "inf", "-inf" for non-finite values.
std::string format_shortest(double v);

/// `v` with `digits` digits after the decimal point (iostream std::fixed).
std::string format_fixed(double v, int digits);

/// `v` with at most `digits` significant digits (iostream default notation,
/// std::setprecision(digits)): figures in reports, e.g. 0.1235 or 1.235e+04 for digits = 4.
std::string format_significant(double v, int digits);

/// Makes `out` print every double as format_shortest() does (the shortest text that reads
/// back as the same double). The config writers use it, so that what they write, the strict
/// loaders read back to the last bit, and 0.02 stays "0.02" (not 0.020000000000000000).
void use_shortest_round_trip(std::ostream& out);

}  // namespace common
