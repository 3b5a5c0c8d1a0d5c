// Doubles written exactly as an ostream with precision(p) writes them (printf's "%.pg"), through
// std::to_chars: the same bytes, without glibc's printf, which formats 17 significant digits
// with multiprecision arithmetic (on a 1M-triangle reference the field and mesh files spent
// ~8 s there).
#pragma once

#include <charconv>
#include <ostream>
#include <string>

namespace pqlayout {

// Appends x to *out.
inline void AppendNumber(std::string* out, double x, int precision) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::general, precision);
  out->append(buffer, result.ptr);
}

// Writes x to out.
inline void WriteNumber(std::ostream& out, double x, int precision) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::general, precision);
  out.write(buffer, result.ptr - buffer);
}

}  // namespace pqlayout
