// Shared by the CalculiX tests (calculix_test.cc) and the analyze stage's tests
// (analyze_stage_test.cc): a cylindrical test patch, reading decks back, and ccx's presence.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace pqlayout::testing {

// A cylindrical patch (radius R about the y axis, θ = −40°..40°, y = 0..4) as the reference
// surface and as the "planarised" quad mesh (its quads are planar).
struct Cylinder {
  static constexpr int ni = 9, nj = 5;
  static constexpr double R = 10.0;
  static double Theta(int i) { return (-40.0 + 10.0 * i) * M_PI / 180.0; }
  static Eigen::Vector3d Point(int i, int j) { return {R * std::sin(Theta(i)), double(j), R * std::cos(Theta(i))}; }
  static int Id(int i, int j) { return j * ni + i; }
};

inline std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

inline std::vector<double> Numbers(const std::string& line) {
  std::vector<double> v;
  std::string s = line;
  for (char& c : s)
    if (c == ',') c = ' ';
  std::istringstream in(s);
  for (double x; in >> x;) v.push_back(x);
  return v;
}

// Per element set "M<e>" (or the U1 twins "N<e>"): the orientation line of its *BEAM SECTION (the member's local z).
inline std::map<int, Eigen::Vector3d> SectionDirections(const std::string& deck, char set = 'M') {
  std::map<int, Eigen::Vector3d> dirs;
  const auto lines = Lines(deck);
  for (size_t i = 0; i + 2 < lines.size(); ++i)
    if (lines[i].rfind(std::string("*BEAM SECTION, ELSET=") + set, 0) == 0) {
      const int e = std::stoi(lines[i].substr(22)) - 1;
      const std::vector<double> d = Numbers(lines[i + 2]);
      dirs[e] = Eigen::Vector3d(d.at(0), d.at(1), d.at(2));
    }
  return dirs;
}

// ccx's .dat has 7 significant digits; summing a few dozen such products stays well inside this.
inline constexpr double kPrintoutTolerance = 1e-5;

inline bool HaveCcx() { return std::system("command -v ccx > /dev/null 2>&1") == 0; }

#define REQUIRE_CCX()                                                                                  \
  if (!pqlayout::testing::HaveCcx()) GTEST_SKIP() << "ccx is not installed (Debian package calculix-ccx): "               \
                                  "the CalculiX cross-check did not run"


}  // namespace pqlayout::testing
