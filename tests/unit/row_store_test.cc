// RowStore and FileBlockSpill: rows come back exactly as appended whether they stayed in
// memory or went to disk, spill files never outlive the store, IO errors name the file.
#include "solver/sparse/row_store.h"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "solver/sparse/file_block_spill.h"

namespace radflux {
namespace {

namespace fs = std::filesystem;

// Row i (of n) has entries at columns (i + 7 k) mod n for k < i % 5, value i + k / 8.
RowBlock MakeBlock(uint32_t first, uint32_t count, uint32_t n) {
  RowBlock block;
  block.first_row = first;
  for (uint32_t i = first; i < first + count; ++i) {
    std::vector<uint32_t> cols;
    for (uint32_t k = 0; k < i % 5; ++k) cols.push_back((i + 7 * k) % n);
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    for (size_t k = 0; k < cols.size(); ++k) block.Add(cols[k], static_cast<float>(i + k / 8.0));
    block.EndRow();
  }
  return block;
}

CsrMatrix Expected(uint32_t n, uint32_t block_rows) {
  CsrMatrix m;
  m.cols = n;
  for (uint32_t first = 0; first < n; first += block_rows)
    m.Append(MakeBlock(first, std::min(block_rows, n - first), n));
  return m;
}

// Every row ForEach yields, reassembled.
CsrMatrix Collect(const RowStore& store) {
  CsrMatrix m;
  m.cols = store.cols();
  absl::Status s = store.ForEach([&](const RowsView& rows) {
    RowBlock block;
    block.first_row = rows.first_row;
    for (uint32_t i = rows.first_row; i < rows.EndRow(); ++i) {
      for (size_t e = 0; e < rows.RowCols(i).size(); ++e)
        block.Add(rows.RowCols(i)[e], rows.RowValues(i)[e]);
      block.EndRow();
    }
    m.Append(block);
  });
  EXPECT_TRUE(s.ok()) << s;
  return m;
}

class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "row_store_test_XXXXXX").string();
    path_ = mkdtemp(pattern.data());
  }
  ~TempDir() { fs::remove_all(path_); }
  const std::string& path() const { return path_; }
  bool Empty() const { return fs::is_empty(path_); }

 private:
  std::string path_;
};

void AppendAll(RowStore& store, uint32_t n, uint32_t block_rows) {
  for (uint32_t first = 0; first < n; first += block_rows) {
    const absl::Status s = store.Append(MakeBlock(first, std::min(block_rows, n - first), n));
    ASSERT_TRUE(s.ok()) << s;
  }
  const absl::Status s = store.Finish();
  ASSERT_TRUE(s.ok()) << s;
}

TEST(RowStore, SpilledRowsComeBackExactlyInEveryPass) {
  const uint32_t n = 1000, block_rows = 16;
  const CsrMatrix expected = Expected(n, block_rows);
  TempDir dir;
  // Chunks of ~1 KB and a 4 KB budget: a few chunks stay, most go to disk.
  RowStore store(n, 4096, std::make_unique<FileBlockSpill>(dir.path()), 1024);
  AppendAll(store, n, block_rows);
  EXPECT_EQ(store.rows(), n);
  EXPECT_EQ(store.nnz(), expected.nnz());
  EXPECT_LE(store.MemoryBytes(), 4096u);
  EXPECT_GT(store.SpilledBytes(), 4 * store.MemoryBytes());
  for (int pass = 0; pass < 3; ++pass) {
    const CsrMatrix got = Collect(store);
    EXPECT_EQ(got.row_begin, expected.row_begin);
    EXPECT_EQ(got.col, expected.col);
    EXPECT_EQ(got.value, expected.value);
  }
  EXPECT_EQ(store.read_stats().passes, 3);
  EXPECT_EQ(store.read_stats().bytes, 3 * store.SpilledBytes());
}

TEST(RowStore, WithinBudgetNothingSpills) {
  const uint32_t n = 300;
  RowStore store(n, uint64_t{1} << 30, nullptr, 1024);
  AppendAll(store, n, 7);
  EXPECT_EQ(store.SpilledBytes(), 0u);
  EXPECT_EQ(Collect(store).col, Expected(n, 7).col);
}

TEST(RowStore, RefusesBlocksOutOfOrderAndColumnsOutOfRange) {
  RowStore store(10, 1 << 20, nullptr);
  EXPECT_EQ(store.Append(MakeBlock(5, 2, 10)).code(), absl::StatusCode::kInvalidArgument);
  RowBlock bad;
  bad.Add(10, 0.5f);
  bad.EndRow();
  const absl::Status s = store.Append(bad);
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("column 10 >= 10"), std::string::npos) << s;
}

TEST(FileBlockSpill, FilesAreGoneWhileAndAfterTheStoreLives) {
  TempDir dir;
  {
    RowStore store(100, 0, std::make_unique<FileBlockSpill>(dir.path()), 256);
    AppendAll(store, 100, 10);
    EXPECT_GT(store.SpilledBytes(), 0u);
    EXPECT_TRUE(dir.Empty());  // unlinked at creation: a killed process leaves nothing
    EXPECT_EQ(Collect(store).value, Expected(100, 10).value);
  }
  EXPECT_TRUE(dir.Empty());
}

TEST(FileBlockSpill, DefaultDirectoryUnderTmpdirIsRemoved) {
  TempDir tmp;
  const char* old = getenv("TMPDIR");
  const std::string saved = old != nullptr ? old : "";
  setenv("TMPDIR", tmp.path().c_str(), 1);
  {
    RowStore store(100, 0, std::make_unique<FileBlockSpill>(""), 256);
    AppendAll(store, 100, 10);
    ASSERT_FALSE(tmp.Empty());
    EXPECT_EQ(
        fs::directory_iterator(tmp.path())->path().filename().string().rfind("radflux-spill-", 0),
        0u);
  }
  EXPECT_TRUE(tmp.Empty());
  if (old != nullptr) {
    setenv("TMPDIR", saved.c_str(), 1);
  } else {
    unsetenv("TMPDIR");
  }
}

TEST(FileBlockSpill, UnwritableDirectoryIsAClearError) {
  TempDir dir;
  const std::string not_a_dir = dir.path() + "/plain_file";
  std::ofstream(not_a_dir) << "x";  // a file where a directory should be (root can't bypass)
  RowStore store(100, 0, std::make_unique<FileBlockSpill>(not_a_dir), 256);
  const absl::Status s = store.Append(MakeBlock(0, 100, 100));
  EXPECT_EQ(s.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_NE(s.message().find("cannot create a spill file in '" + not_a_dir + "'"),
            std::string::npos)
      << s;
  EXPECT_NE(s.message().find("Not a directory"), std::string::npos) << s;
}

// A spill whose reads fail after `good` blocks.
class FailingSpill : public BlockSpill {
 public:
  explicit FailingSpill(size_t good) : good_(good) {}
  absl::Status Write(const RowBlock& block) override {
    blocks_.push_back(block);
    return absl::OkStatus();
  }
  absl::Status Read(size_t index, RowBlock& out) const override {
    if (index >= good_) return absl::DataLossError("spill 'fake': reading block failed");
    out = blocks_[index];
    return absl::OkStatus();
  }
  uint64_t BytesWritten() const override { return 0; }

 private:
  size_t good_;
  std::vector<RowBlock> blocks_;
};

TEST(RowStore, ReadErrorStopsTheStreamAndComesBack) {
  RowStore store(100, 0, std::make_unique<FailingSpill>(2), 64);
  AppendAll(store, 100, 5);
  uint32_t rows_seen = 0;
  const absl::Status s = store.ForEach([&](const RowsView& rows) { rows_seen += rows.RowCount(); });
  EXPECT_EQ(s.code(), absl::StatusCode::kDataLoss);
  EXPECT_GT(rows_seen, 0u);
  EXPECT_LT(rows_seen, 100u);
}

}  // namespace
}  // namespace radflux
