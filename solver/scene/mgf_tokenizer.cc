#include "solver/scene/mgf_tokenizer.h"

#include <charconv>
#include <cmath>

namespace radflux {
namespace {

bool IsSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

// Appends the words of `line` to `words`.
void SplitWords(std::string_view line, std::vector<std::string>& words) {
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && IsSpace(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !IsSpace(line[i])) ++i;
    if (i > start) words.emplace_back(line.substr(start, i - start));
  }
}

// `line` without its trailing white space; sets `continued` when it then ends in '\'.
std::string_view TrimContinuation(std::string_view line, bool* continued) {
  while (!line.empty() && IsSpace(line.back())) line.remove_suffix(1);
  *continued = !line.empty() && line.back() == '\\';
  if (*continued) line.remove_suffix(1);
  return line;
}

}  // namespace

std::vector<MgfStatement> TokenizeMgf(std::string_view text) {
  std::vector<MgfStatement> statements;
  MgfStatement current;
  bool continuing = false;
  int line_number = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    ++line_number;
    bool continued = false;
    const std::string_view line = TrimContinuation(text.substr(pos, end - pos), &continued);
    pos = end + 1;
    if (!continuing) current = MgfStatement{line_number, {}};
    SplitWords(line, current.words);
    continuing = continued;
    if (continuing) continue;
    if (!current.words.empty() && current.words[0][0] != '#') {
      statements.push_back(std::move(current));
    }
  }
  if (continuing && !current.words.empty() && current.words[0][0] != '#') {
    statements.push_back(std::move(current));
  }
  return statements;
}

bool ParseMgfNumber(std::string_view word, double* value) {
  if (!word.empty() && word[0] == '+') word.remove_prefix(1);
  if (word.empty() || word[0] == '+') return false;
  const char* end = word.data() + word.size();
  const auto [ptr, ec] = std::from_chars(word.data(), end, *value);
  return ec == std::errc() && ptr == end && std::isfinite(*value);
}

bool ParseMgfInteger(std::string_view word, long long* value) {
  if (!word.empty() && word[0] == '+') word.remove_prefix(1);
  if (word.empty() || word[0] == '+') return false;
  const char* end = word.data() + word.size();
  const auto [ptr, ec] = std::from_chars(word.data(), end, *value);
  constexpr long long kLimit = 1LL << 62;
  return ec == std::errc() && ptr == end && *value <= kLimit && *value >= -kLimit;
}

}  // namespace radflux
