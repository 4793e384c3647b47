// MGF text as statements: one entity per logical line (a line ending in a backslash goes on
// on the next line), split into whitespace-separated words, with the line where it starts.
// Comment lines ('#') and blank lines are dropped. Numbers are read strictly.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace radflux {

struct MgfStatement {
  int line = 0;                    // 1-based line where the statement starts
  std::vector<std::string> words;  // words[0] is the entity name ("f", "xf", ...), never empty
};

// The statements of `text` in order. Never fails: what the words mean is checked later.
std::vector<MgfStatement> TokenizeMgf(std::string_view text);

// `word` as a finite double (e.g. "-.0254", "1e3", "+2"); false if it is anything else.
bool ParseMgfNumber(std::string_view word, double* value);

// `word` as an integer in [-2^62, 2^62]; false if it is anything else (e.g. "2.5", "x").
bool ParseMgfInteger(std::string_view word, long long* value);

}  // namespace radflux
