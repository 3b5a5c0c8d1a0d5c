#include "geometry/text_reader.h"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <fstream>

namespace pqlayout {

Status ReadFileBytes(const std::string& path, std::string* bytes) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return Status::InvalidInput(path + ": cannot open file");
  // One read into a buffer of the file's size: streaming into a growing string copies it
  // several times, which was most of the time spent on a large mesh.
  const std::streamoff size = in.tellg();
  if (size < 0) return Status::InvalidInput(path + ": cannot read file");
  bytes->resize(static_cast<size_t>(size));
  in.seekg(0);
  if (!in.read(bytes->data(), size)) return Status::InvalidInput(path + ": cannot read file");
  return Status::Ok();
}

bool LineScanner::Next(std::string_view* line) {
  if (offset_ >= text_.size()) return false;
  const size_t end = std::min(text_.find('\n', offset_), text_.size());
  *line = text_.substr(offset_, end - offset_);
  if (!line->empty() && line->back() == '\r') line->remove_suffix(1);
  offset_ = std::min(end + 1, text_.size());
  ++line_number_;
  return true;
}

namespace {
bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
}  // namespace

void SplitWords(std::string_view line, std::vector<std::string_view>* words) {
  words->clear();
  size_t at = 0;
  while (at < line.size()) {
    while (at < line.size() && IsBlank(line[at])) ++at;
    const size_t start = at;
    while (at < line.size() && !IsBlank(line[at])) ++at;
    if (at > start) words->push_back(line.substr(start, at - start));
  }
}

bool WordScanner::Next(std::string_view* word) {
  while (next_ >= words_.size()) {
    std::string_view line;
    if (!lines_.Next(&line)) return false;
    SplitWords(line, &words_);
    next_ = 0;
  }
  *word = words_[next_++];
  return true;
}

namespace {
// std::from_chars takes no '+' sign: drop one, but refuse "+-1" and "++1".
bool DropPlusSign(std::string_view* word) {
  if (word->empty() || word->front() != '+') return true;
  word->remove_prefix(1);
  return word->empty() || (word->front() != '-' && word->front() != '+');
}
}  // namespace

bool ParseDouble(std::string_view word, double* value) {
  if (!DropPlusSign(&word) || word.empty()) return false;
  const char* end = word.data() + word.size();
  const auto [stop, error] = std::from_chars(word.data(), end, *value);
  if (stop != end) return false;
  if (error == std::errc()) return true;
  if (error != std::errc::result_out_of_range) return false;
  // Beyond double's range: what strtod gives (inf, for the caller to refuse, or 0).
  *value = std::strtod(std::string(word).c_str(), nullptr);
  return true;
}

bool ParseInteger(std::string_view word, long long* value) {
  if (!DropPlusSign(&word)) return false;
  const char* end = word.data() + word.size();
  const auto [stop, error] = std::from_chars(word.data(), end, *value);
  return error == std::errc() && stop == end;
}

bool CountFits(long long count, long long bytes_each, size_t bytes) {
  return count >= 0 && bytes_each > 0 && static_cast<unsigned long long>(count) <= bytes / bytes_each;
}

std::string Quote(std::string_view word) {
  constexpr size_t kMax = 40;
  std::string out = "'";
  for (size_t k = 0; k < word.size() && k < kMax; ++k) {
    const unsigned char c = static_cast<unsigned char>(word[k]);
    out += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  }
  if (word.size() > kMax) out += "...";
  return out + "'";
}

std::string NoSuchVertex(long long index, long long n_vertices) {
  return "vertex index " + std::to_string(index) + " names no vertex (the file has " + std::to_string(n_vertices) + ")";
}

Status LineError(const std::string& path, int line, const std::string& message) {
  return Status::InvalidInput(path + ":" + std::to_string(line) + ": " + message);
}

}  // namespace pqlayout
