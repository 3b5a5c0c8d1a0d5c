// Reading SVG output in tests: the file's text, counting a substring, the document's frame.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace pqlayout::testing {

inline std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

inline void ExpectSvgDocument(const std::string& svg) {
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  const size_t end = svg.find_last_not_of(" \n");
  ASSERT_NE(end, std::string::npos);
  EXPECT_EQ(svg.substr(end + 1 - 6, 6), "</svg>");
  EXPECT_EQ(Count(svg, "<svg"), 1);
}

}  // namespace pqlayout::testing
