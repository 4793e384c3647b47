#include "server/store/stored_codec.h"

#include <cstring>
#include <type_traits>

namespace radflux {
namespace {

constexpr uint32_t kRowBlockTag = 0x52424c31;         // "RBL1"
constexpr uint32_t kRowBlockGroupTag = 0x52424731;    // "RBG1": count, then sized blocks
constexpr uint32_t kViewFactorBlockTag = 0x56464231;  // "VFB1": first row, rows, values
constexpr uint32_t kCheckpointTag = 0x43504b31;       // "CPK1": iteration, B
constexpr uint32_t kCheckpointTag2 = 0x43504b32;      // "CPK2": iteration, B, method, unshot

// Appends trivially copyable values (the platforms radflux runs on are little-endian).
class Writer {
 public:
  template <typename T>
  void Put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <typename T>
  void PutVector(const std::vector<T>& v) {
    Put<uint64_t>(v.size());
    out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void PutBytes(std::string_view bytes) { out_.append(bytes); }
  std::string Take() { return std::move(out_); }

 private:
  std::string out_;
};

// Reads what Writer wrote; every read checks the remaining length.
class Reader {
 public:
  explicit Reader(std::string_view in) : in_(in) {}
  template <typename T>
  bool Get(T& v) {
    if (in_.size() < sizeof(T)) return false;
    std::memcpy(&v, in_.data(), sizeof(T));
    in_.remove_prefix(sizeof(T));
    return true;
  }
  template <typename T>
  bool GetVector(std::vector<T>& v) {
    uint64_t size = 0;
    if (!Get(size) || size > in_.size() / sizeof(T)) return false;
    v.resize(size);
    if (size > 0) std::memcpy(v.data(), in_.data(), size * sizeof(T));  // data() may be null
    in_.remove_prefix(size * sizeof(T));
    return true;
  }
  // The next `size` bytes as a view into the input.
  bool GetBytes(uint64_t size, std::string_view& v) {
    if (size > in_.size()) return false;
    v = in_.substr(0, size);
    in_.remove_prefix(size);
    return true;
  }
  bool AtEnd() const { return in_.empty(); }

 private:
  std::string_view in_;
};

}  // namespace

std::string EncodeRowBlock(const StoredRowBlock& stored) {
  Writer w;
  if (stored.view_factors) {
    w.Put(kViewFactorBlockTag);
    w.Put(stored.block.first_row);
    w.Put(stored.block.RowCount());
    w.PutVector(stored.values);
    return w.Take();
  }
  w.Put(kRowBlockTag);
  w.Put(stored.block.first_row);
  w.PutVector(stored.block.row_begin);
  w.PutVector(stored.block.col);
  w.PutVector(stored.block.value);
  w.Put(stored.stats.rays);
  w.Put(stored.stats.dropped_sum);
  w.Put(stored.stats.max_row_dropped);
  // The rows the cap scaled back, as two vectors (absent in blocks stored before them).
  std::vector<uint32_t> scaled_rows;
  std::vector<double> scaled_sums;
  for (const ScaledRow& s : stored.stats.scaled_off) {
    scaled_rows.push_back(s.row);
    scaled_sums.push_back(s.removed);
  }
  w.PutVector(scaled_rows);
  w.PutVector(scaled_sums);
  return w.Take();
}

namespace {

// The rest of a view-factor block after its tag (at most 2^20 rows: nothing huge allocated).
absl::StatusOr<StoredRowBlock> DecodeViewFactorBlock(Reader& r) {
  StoredRowBlock s;
  s.view_factors = true;
  uint32_t rows = 0;
  if (!r.Get(s.block.first_row) || !r.Get(rows) || !r.GetVector(s.values) || !r.AtEnd() ||
      rows > (uint32_t{1} << 20)) {
    return absl::DataLossError("not a view-factor row block");
  }
  s.block.row_begin.assign(rows + 1, 0);
  return s;
}

}  // namespace

namespace {

// The scaled rows at the end of a row block, if any (blocks stored before them end here):
// true when the reader is then at its end.
bool DecodeScaledRows(Reader& r, RowBlockStats& stats) {
  if (r.AtEnd()) return true;
  std::vector<uint32_t> rows;
  std::vector<double> sums;
  if (!r.GetVector(rows) || !r.GetVector(sums) || rows.size() != sums.size() || !r.AtEnd()) {
    return false;
  }
  for (size_t k = 0; k < rows.size(); ++k) stats.scaled_off.push_back({rows[k], sums[k]});
  return true;
}

}  // namespace

absl::StatusOr<StoredRowBlock> DecodeRowBlock(std::string_view bytes) {
  Reader r(bytes);
  StoredRowBlock s;
  uint32_t tag = 0;
  if (r.Get(tag) && tag == kViewFactorBlockTag) return DecodeViewFactorBlock(r);
  const bool ok = tag == kRowBlockTag && r.Get(s.block.first_row) &&
                  r.GetVector(s.block.row_begin) && r.GetVector(s.block.col) &&
                  r.GetVector(s.block.value) && r.Get(s.stats.rays) && r.Get(s.stats.dropped_sum) &&
                  r.Get(s.stats.max_row_dropped) && DecodeScaledRows(r, s.stats);
  if (!ok || s.block.row_begin.empty() || s.block.col.size() != s.block.value.size() ||
      s.block.row_begin.back() != s.block.col.size()) {
    return absl::DataLossError("not a row block");
  }
  return s;
}

std::string EncodeRowBlockGroup(const std::vector<const StoredRowBlock*>& blocks) {
  Writer w;
  w.Put(kRowBlockGroupTag);
  w.Put<uint64_t>(blocks.size());
  for (const StoredRowBlock* block : blocks) {
    const std::string bytes = EncodeRowBlock(*block);
    w.Put<uint64_t>(bytes.size());
    w.PutBytes(bytes);
  }
  return w.Take();
}

absl::StatusOr<std::vector<StoredRowBlock>> DecodeRowBlockGroup(std::string_view bytes) {
  Reader r(bytes);
  uint32_t tag = 0;
  uint64_t count = 0;
  if (!r.Get(tag) || tag != kRowBlockGroupTag || !r.Get(count) || count > bytes.size()) {
    return absl::DataLossError("not a row block group");
  }
  std::vector<StoredRowBlock> blocks;
  blocks.reserve(count);
  for (uint64_t k = 0; k < count; ++k) {
    uint64_t size = 0;
    std::string_view block;
    if (!r.Get(size) || !r.GetBytes(size, block)) {
      return absl::DataLossError("row block group truncated");
    }
    absl::StatusOr<StoredRowBlock> decoded = DecodeRowBlock(block);
    if (!decoded.ok()) return decoded.status();
    blocks.push_back(*std::move(decoded));
  }
  if (!r.AtEnd()) return absl::DataLossError("row block group has trailing bytes");
  return blocks;
}

std::string EncodeCheckpoint(const SolverCheckpoint& checkpoint) {
  Writer w;
  w.Put(kCheckpointTag2);
  w.Put(checkpoint.iteration);
  w.PutVector(checkpoint.radiosity);
  w.Put(checkpoint.method);
  w.PutVector(checkpoint.unshot);
  return w.Take();
}

absl::StatusOr<SolverCheckpoint> DecodeCheckpoint(std::string_view bytes) {
  Reader r(bytes);
  SolverCheckpoint c;
  uint32_t tag = 0;
  const bool ok = r.Get(tag) && (tag == kCheckpointTag || tag == kCheckpointTag2) &&
                  r.Get(c.iteration) && r.GetVector(c.radiosity) &&
                  (tag == kCheckpointTag || (r.Get(c.method) && r.GetVector(c.unshot))) &&
                  r.AtEnd();
  if (!ok || (!c.unshot.empty() && c.unshot.size() != c.radiosity.size())) {
    return absl::DataLossError("not a solver checkpoint");
  }
  return c;
}

}  // namespace radflux
