// What the mesh readers (mesh_readers.h) share: the whole file in memory, a scanner over its
// lines and words that knows the line number, whole-word number parsing, and messages that
// can quote a word from a binary file and still be one readable line.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "base/status.h"

namespace pqlayout {

// Reads the whole file, bytes as they are. InvalidInput "PATH: cannot open file" if it cannot.
Status ReadFileBytes(const std::string& path, std::string* bytes);

// Walks text line by line ("\n" or "\r\n" endings), numbering lines from first_line.
class LineScanner {
 public:
  explicit LineScanner(std::string_view text, int first_line = 1)
      : text_(text), line_number_(first_line - 1) {}
  // The next line without its ending; false at the end of the text.
  bool Next(std::string_view* line);
  // The number of the line last returned.
  int line_number() const { return line_number_; }
  // Where the next line starts (the first byte after the last line's ending).
  size_t offset() const { return offset_; }

 private:
  std::string_view text_;
  size_t offset_ = 0;
  int line_number_;
};

// Splits a line into words separated by blanks (space, tab, CR, VT, FF).
void SplitWords(std::string_view line, std::vector<std::string_view>* words);

// Walks text word by word across line breaks, for formats whose values need not be laid out
// one item per line (ASCII PLY).
class WordScanner {
 public:
  explicit WordScanner(std::string_view text, int first_line = 1) : lines_(text, first_line) {}
  // The next word; false at the end of the text.
  bool Next(std::string_view* word);
  // The line of the word last returned (or the last line, at the end of the text).
  int line_number() const { return lines_.line_number(); }

 private:
  LineScanner lines_;
  std::vector<std::string_view> words_;
  size_t next_ = 0;
};

// Whole-word parsing, independent of the locale: false unless all of the word is one number
// ("1.5x" and "" are not; a leading '+' is allowed). ParseDouble gives inf for "1e999" and
// "inf", NaN for "nan": the caller decides about non-finite values. ParseInteger is false for
// values beyond the range of long long.
bool ParseDouble(std::string_view word, double* value);
bool ParseInteger(std::string_view word, long long* value);

// Whether `count` items of at least `bytes_each` bytes fit in `bytes` bytes (false if negative).
bool CountFits(long long count, long long bytes_each, size_t bytes);

// The word in single quotes, cut to 40 characters, with anything unprintable shown as '?',
// so that a message about a binary file stays one readable line.
std::string Quote(std::string_view word);

// "vertex index INDEX names no vertex (the file has N_VERTICES)": what every reader says of a
// face corner out of range.
std::string NoSuchVertex(long long index, long long n_vertices);

// InvalidInput "PATH:LINE: message".
Status LineError(const std::string& path, int line, const std::string& message);

}  // namespace pqlayout
