#include "server/api/tokens_file.h"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"

namespace radflux {
namespace {

constexpr size_t kMaxPrincipalName = 64;

bool ValidName(const std::string& name) {
  if (name.empty() || name.size() > kMaxPrincipalName) return false;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '.' || c == '@' || c == '-';
    if (!ok) return false;
  }
  return true;
}

// The whitespace-separated fields of a line, up to a field that starts with '#'.
std::vector<std::string> Fields(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> fields;
  for (std::string field; in >> field;) {
    if (field[0] == '#') break;
    fields.push_back(field);
  }
  return fields;
}

// Applies one optional field ("admin" or "LIMIT=VALUE") to `principal`; the error says why not.
absl::Status ApplyField(const std::string& field, Principal& principal) {
  if (field == "admin") {
    principal.admin = true;
    return absl::OkStatus();
  }
  const size_t eq = field.find('=');
  const std::string key = field.substr(0, eq);
  const std::string value = eq == std::string::npos ? "" : field.substr(eq + 1);
  PrincipalLimits& limits = principal.limits;
  if (key == "running_jobs" || key == "patches") {
    int64_t n = 0;
    if (!absl::SimpleAtoi(value, &n) || n < 0) {
      return absl::InvalidArgumentError(
          absl::StrCat(key, " needs a whole number >= 0 (0 = no limit), not '", value, "'"));
    }
    (key == "patches" ? limits.patches : limits.running_jobs) = n;
    return absl::OkStatus();
  }
  if (key == "cpu_seconds") {
    double s = 0;
    if (!absl::SimpleAtod(value, &s) || !std::isfinite(s) || s < 0) {
      return absl::InvalidArgumentError(
          absl::StrCat("cpu_seconds needs a number >= 0 (0 = no limit), not '", value, "'"));
    }
    limits.cpu_seconds = s;
    return absl::OkStatus();
  }
  return absl::InvalidArgumentError(
      absl::StrCat("unknown field '", field,
                   "' (expected admin, running_jobs=N, patches=N or cpu_seconds=S)"));
}

}  // namespace

absl::StatusOr<std::vector<TokenEntry>> ReadTokensFile(const std::string& path,
                                                       const PrincipalLimits& defaults) {
  std::ifstream in(path);
  if (!in) return absl::InvalidArgumentError(absl::StrCat("cannot read tokens file ", path));
  std::vector<TokenEntry> entries;
  std::map<std::string, int> name_lines, token_lines;
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    const auto error = [&](const std::string& what) {
      return absl::InvalidArgumentError(absl::StrCat(path, ":", line_number, ": ", what));
    };
    const std::vector<std::string> fields = Fields(line);
    if (fields.empty()) continue;
    if (fields.size() < 2) {
      return error("expected 'PRINCIPAL TOKEN [admin] [running_jobs=N] [patches=N] "
                   "[cpu_seconds=S]' (TOKEN '-': TLS client certificate only)");
    }
    TokenEntry entry;
    entry.principal.name = fields[0];
    entry.principal.limits = defaults;
    if (!ValidName(fields[0])) {
      return error(absl::StrCat("bad principal name '", fields[0],
                                "' (1-64 of A-Z a-z 0-9 _ . @ -)"));
    }
    if (auto [it, added] = name_lines.emplace(fields[0], line_number); !added) {
      return error(absl::StrCat("principal '", fields[0], "' already defined on line ",
                                it->second));
    }
    if (fields[1] != "-") {
      entry.token = fields[1];
      if (auto [it, added] = token_lines.emplace(fields[1], line_number); !added) {
        return error(absl::StrCat("the token of '", fields[0], "' is already the token of line ",
                                  it->second));
      }
    }
    for (size_t i = 2; i < fields.size(); ++i) {
      if (absl::Status s = ApplyField(fields[i], entry.principal); !s.ok()) {
        return error(std::string(s.message()));
      }
    }
    entries.push_back(std::move(entry));
  }
  return entries;
}

}  // namespace radflux
