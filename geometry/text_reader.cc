#include "geometry/text_reader.h"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace pqlayout {

Status ReadFileBytes(const std::string& path, std::string* bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Status::InvalidInput(path + ": cannot open file");
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad()) return Status::InvalidInput(path + ": cannot read file");
  *bytes = std::move(content).str();
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

bool ParseDouble(std::string_view word, double* value) {
  // strtod needs a terminated string; words are short, so the copy stays on the stack.
  const std::string text(word);
  if (text.empty()) return false;
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

bool ParseInteger(std::string_view word, long long* value) {
  // from_chars takes no '+' sign; allow one, but not "+-1".
  if (!word.empty() && word.front() == '+') {
    word.remove_prefix(1);
    if (!word.empty() && word.front() == '-') return false;
  }
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), *value);
  return error == std::errc() && end == word.data() + word.size();
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

Status LineError(const std::string& path, int line, const std::string& message) {
  return Status::InvalidInput(path + ":" + std::to_string(line) + ": " + message);
}

}  // namespace pqlayout
