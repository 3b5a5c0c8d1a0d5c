// How the SVG writer (svg_canvas.cc, svg_canvas_keys.cc) prints numbers and measures text.
// Internal to report/svg_canvas*.cc; inline, since every coordinate of every figure goes
// through Number.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

namespace pqlayout {
namespace svg_format {

// Appends `value` rounded to `decimals` decimals, without trailing zeros ("12.3", "-4", "0").
inline void AppendNumber(std::string* out, double value, int decimals = 1) {
  static constexpr long long kPow10[] = {1, 10, 100, 1000, 10000};
  const long long scale = kPow10[decimals];
  long long q = std::llround(value * static_cast<double>(scale));
  if (q < 0) {
    out->push_back('-');
    q = -q;
  }
  *out += std::to_string(q / scale);
  long long frac = q % scale;
  if (frac == 0) return;
  std::string digits = std::to_string(frac);
  digits.insert(0, static_cast<size_t>(decimals) - digits.size(), '0');
  digits.erase(digits.find_last_not_of('0') + 1);
  *out += '.' + digits;
}

inline std::string Number(double value, int decimals = 1) {
  std::string s;
  AppendNumber(&s, value, decimals);
  return s;
}

inline std::string EscapeXml(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Number of characters (UTF-8 code points), for text-width estimates.
inline int CodePoints(const std::string& text) {
  return static_cast<int>(
      std::count_if(text.begin(), text.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

// "×10⁻⁵" for exponent -5.
inline std::string PowerOfTen(int exponent) {
  static const char* kSuperscript[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string digits;
  for (const char c : std::to_string(std::abs(exponent))) digits += kSuperscript[c - '0'];
  return std::string("×10") + (exponent < 0 ? "⁻" : "") + digits;
}

// Decimals needed to print multiples of `step` exactly (step from NiceTicks).
inline int DecimalsFor(double step) {
  return std::clamp(static_cast<int>(std::ceil(-std::log10(step) - 1e-9)), 0, 4);
}

}  // namespace svg_format
}  // namespace pqlayout
