#include "solver/formfactor/view_factor_writer.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace radflux {
namespace {

std::string CsvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string quoted = "\"";
  for (char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

// Appends `v` as printf would with "%.<precision>f" (fixed) or "%.<precision>g" (general):
// std::to_chars with a precision is specified as printf in the C locale, without its cost.
void AppendNumber(std::string& out, double v, std::chars_format format, int precision) {
  char buffer[64];
  const std::to_chars_result r = std::to_chars(buffer, buffer + sizeof(buffer), v, format, precision);
  out.append(buffer, r.ptr);
}

// Writes `v` at `out` as AppendNumber(., v, fixed, 6) would, the same characters, and returns
// the end; `out` needs room for kFixed6Room characters. Fast for the values a view-factor row
// holds: for 0 <= v < 1000, round(v 10^6) from the product v * 10^6 (within 6e-8 of the exact
// one), unless its fraction is within 1e-6 of one half, where the exact value decides and
// to_chars is asked (as it is for other values).
constexpr size_t kFixed6Room = 400;  // "-" + 309 digits + "." + 6 digits, and more
char* PutFixed6(char* out, double v) {
  const double scaled = v * 1e6;
  const double whole = std::floor(scaled);
  if (std::signbit(v) || !(v < 1000) || std::abs(scaled - whole - 0.5) < 1e-6) {
    return std::to_chars(out, out + kFixed6Room, v, std::chars_format::fixed, 6).ptr;
  }
  const uint64_t q = static_cast<uint64_t>(whole) + (scaled - whole > 0.5 ? 1 : 0);
  char* end = out;
  if (q < 1000000) {
    *end++ = '0';  // most view factors
  } else {
    end = std::to_chars(out, out + kFixed6Room, q / 1000000).ptr;
  }
  *end++ = '.';
  // The six decimals two at a time from a table of "00" to "99".
  static constexpr auto kPairs = [] {
    std::array<char, 200> pairs{};
    for (int k = 0; k < 100; ++k) {
      pairs[2 * k] = static_cast<char>('0' + k / 10);
      pairs[2 * k + 1] = static_cast<char>('0' + k % 10);
    }
    return pairs;
  }();
  uint64_t fraction = q % 1000000;
  for (int k = 4; k >= 0; k -= 2, fraction /= 100) {
    std::memcpy(end + k, kPairs.data() + 2 * (fraction % 100), 2);
  }
  return end + 6;
}

// `line` := the values separated by spaces, each as PutFixed6 writes it, written in place.
void FormatFixed6Row(std::span<const double> row, std::string& line) {
  line.resize(std::max(line.size(), 11 * row.size() + kFixed6Room));  // 10 + 1 a value usually
  size_t at = 0;
  for (size_t j = 0; j < row.size(); ++j) {
    if (line.size() - at < kFixed6Room + 1) line.resize(2 * line.size());
    if (j > 0) line[at++] = ' ';
    at = static_cast<size_t>(PutFixed6(line.data() + at, row[j]) - line.data());
  }
  line.resize(at);
}

absl::StatusOr<std::FILE*> OpenFile(const std::string& path, const char* kind) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) {
    return absl::InvalidArgumentError(
        absl::StrCat("cannot write ", kind, " file '", path, "': ", std::strerror(errno)));
  }
  return f;
}

// Closes `f` (if open); INTERNAL naming `path` when any write to it failed.
absl::Status CloseFile(std::FILE*& f, const std::string& path) {
  if (f == nullptr) return absl::OkStatus();
  const bool failed = std::ferror(f) != 0;
  const bool close_failed = std::fclose(f) != 0;
  f = nullptr;
  if (failed || close_failed) return absl::InternalError(absl::StrCat("writing '", path, "' failed"));
  return absl::OkStatus();
}

}  // namespace

std::optional<ViewFactorFormat> ParseViewFactorFormat(std::string_view name) {
  if (name == "csv") return ViewFactorFormat::kCsv;
  if (name == "sparse") return ViewFactorFormat::kSparse;
  if (name == "view3d") return ViewFactorFormat::kView3d;
  return std::nullopt;
}

absl::StatusOr<std::unique_ptr<ViewFactorWriter>> ViewFactorWriter::Open(
    const ViewFactorOutput& output, ViewFactorSurfaces surfaces) {
  std::unique_ptr<ViewFactorWriter> writer(new ViewFactorWriter(output, std::move(surfaces)));
  absl::StatusOr<std::FILE*> file = OpenFile(output.path, "view-factor");
  if (!file.ok()) return file.status();
  writer->file_ = *file;
  if (!output.svf_path.empty()) {
    absl::StatusOr<std::FILE*> svf = OpenFile(output.svf_path, "sky-view-factor");
    if (!svf.ok()) return svf.status();
    writer->svf_ = *svf;
    std::fputs("# sky view factors\n", writer->svf_);
  }
  if (absl::Status s = writer->WriteHeader(); !s.ok()) return s;
  return writer;
}

ViewFactorWriter::~ViewFactorWriter() {
  if (file_ != nullptr) std::fclose(file_);
  if (svf_ != nullptr) std::fclose(svf_);
}

absl::Status ViewFactorWriter::WriteHeader() {
  const size_t n = surfaces_.names.size();
  if (output_.format == ViewFactorFormat::kCsv) {
    std::fputs("from", file_);
    for (const std::string& name : surfaces_.names) absl::FPrintF(file_, ",%s", CsvField(name));
    std::fputc('\n', file_);
  } else if (output_.format == ViewFactorFormat::kView3d) {
    std::string header = absl::StrFormat("radflux 3.2 0 %d %d %d", surfaces_.enclosure ? 1 : 0,
                                         surfaces_.emittances ? 1 : 0, n);
    header.resize(std::max<size_t>(header.size(), 30), ' ');  // View3D pads to 30 characters
    absl::FPrintF(file_, "%s\n", header);
    for (size_t k = 0; k < n; ++k) absl::FPrintF(file_, "%s%g", k ? " " : "", surfaces_.area[k]);
    std::fputc('\n', file_);
  }
  return absl::OkStatus();
}

void ViewFactorWriter::WriteSparseRow(std::span<const double> row) {
  double dropped = 0, total = 0;
  size_t largest = 0;
  bool any_kept = false;
  for (size_t j = 0; j < row.size(); ++j) {
    total += row[j];
    if (row[j] > row[largest]) largest = j;
    if (row[j] > 0 && row[j] < output_.min_vf) dropped += row[j];
    any_kept = any_kept || (row[j] > 0 && row[j] >= output_.min_vf);
  }
  if (total <= 0) return;  // sees nothing: no line
  if (!any_kept) dropped -= row[largest];  // keep the largest entry (see the header)
  for (size_t j = 0; j < row.size(); ++j) {
    const bool kept = row[j] > 0 && (row[j] >= output_.min_vf || (!any_kept && j == largest));
    if (!kept) continue;
    line_.clear();
    absl::StrAppend(&line_, rows_ + 1, " ", j + 1, " ");
    AppendNumber(line_, row[j], std::chars_format::general, 8);
    line_ += ' ';
    AppendNumber(line_, dropped, std::chars_format::general, 8);
    line_ += '\n';
    std::fwrite(line_.data(), 1, line_.size(), file_);
  }
}

absl::Status ViewFactorWriter::WriteRow(std::span<const double> row) {
  const size_t n = surfaces_.names.size();
  if (row.size() != n || rows_ >= n) {
    return absl::InternalError(absl::StrCat("view-factor row ", rows_ + 1, " of ", row.size(),
                                            " values for ", n, " surfaces"));
  }
  switch (output_.format) {
    case ViewFactorFormat::kCsv:
      line_ = CsvField(surfaces_.names[rows_]);
      for (double f : row) {
        line_ += ',';
        AppendNumber(line_, f, std::chars_format::general, 9);
      }
      break;
    case ViewFactorFormat::kSparse:
      WriteSparseRow(row);
      break;
    case ViewFactorFormat::kView3d:
      FormatFixed6Row(row, line_);
      break;
  }
  if (output_.format != ViewFactorFormat::kSparse) {
    line_ += '\n';
    std::fwrite(line_.data(), 1, line_.size(), file_);
  }
  if (svf_ != nullptr) {
    double sum = 0;
    for (double f : row) sum += f;
    absl::FPrintF(svf_, "%.6f\n", std::max(0.0, 1 - sum));
  }
  ++rows_;
  return absl::OkStatus();
}

absl::Status ViewFactorWriter::Close() {
  const size_t n = surfaces_.names.size();
  if (file_ != nullptr && output_.format == ViewFactorFormat::kView3d) {
    for (size_t k = 0; k < n; ++k) {
      absl::FPrintF(file_, "%s%.3f", k ? " " : "", surfaces_.emittance[k]);
    }
    std::fputc('\n', file_);
  }
  absl::Status file = CloseFile(file_, output_.path);
  absl::Status svf = CloseFile(svf_, output_.svf_path);
  if (!file.ok()) return file;
  if (!svf.ok()) return svf;
  if (rows_ != n) {
    return absl::InternalError(absl::StrCat(output_.path, ": ", rows_, " of ", n, " rows written"));
  }
  return absl::OkStatus();
}

}  // namespace radflux
