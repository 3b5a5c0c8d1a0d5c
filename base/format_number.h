// Doubles written exactly as an ostream with precision(p) writes them (printf's "%.pg"), through
// std::to_chars: the same bytes, without glibc's printf, which formats 17 significant digits
// with multiprecision arithmetic (on a 1M-triangle reference the field and mesh files spent
// ~8 s there).
#pragma once

#include <charconv>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>

namespace pqlayout {

// Writes x into buffer (64 bytes suffice for any precision ≤ 40); returns the length.
inline size_t FormatNumber(double x, int precision, char (&buffer)[64]) {
  return std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::general, precision).ptr - buffer;
}

// Appends x to *out.
inline void AppendNumber(std::string* out, double x, int precision) {
  char buffer[64];
  out->append(buffer, FormatNumber(x, precision, buffer));
}

// Writes x to out.
inline void WriteNumber(std::ostream& out, double x, int precision) {
  char buffer[64];
  out.write(buffer, FormatNumber(x, precision, buffer));
}

// A number for a message a person reads: three significant digits, whole numbers from a
// thousand up to 10¹² without an exponent ("0.015", "6180", "4500000", "2.75e+13"), so that
// map coordinates and metre counts read as written.
inline std::string ReadableNumber(double v) {
  std::ostringstream s;
  if (std::abs(v) >= 1e3 && std::abs(v) < 1e12) s << std::llround(v);
  else s << std::setprecision(3) << v;
  return s.str();
}

}  // namespace pqlayout
