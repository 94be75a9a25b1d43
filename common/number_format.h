#pragma once
/// @file number_format.h
/// Numbers as text for files and messages that people and programs read back: the shortest
/// text that reads back as the same double (labels, command lines, summaries), and fixed
/// decimals (timings, percentages).

#include <string>

namespace common {

/// Shortest printf-%g text (15 to 17 significant digits) that strtod reads back as exactly
/// `v`; "nan", "inf", "-inf" for non-finite values.
std::string format_shortest(double v);

/// `v` with `digits` digits after the decimal point (iostream std::fixed).
std::string format_fixed(double v, int digits);

}  // namespace common
