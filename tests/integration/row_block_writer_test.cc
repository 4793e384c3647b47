// RowBlockWriter stores a checkpoint as soon as its queue holds max_group_bytes of rows,
// long before a (here hour-long) checkpoint interval: the rows waiting in memory stay
// bounded whatever the job's size. Every block put is stored, in order, once.
#include "server/store/row_block_writer.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <thread>
#include <vector>

#include "server/store/job_store.h"

namespace radflux {
namespace {

// A block of `rows` rows with 16 entries each (~136 bytes per row), starting at `first`.
std::shared_ptr<const StoredRowBlock> MakeBlock(uint32_t first, uint32_t rows) {
  auto s = std::make_shared<StoredRowBlock>();
  s->block.first_row = first;
  for (uint32_t r = 0; r < rows; ++r) {
    for (uint32_t k = 0; k < 16; ++k) s->block.Add(k, 0.01f * static_cast<float>(first + r));
    s->block.EndRow();
  }
  return s;
}

std::vector<uint32_t> StoredFirstRows(JobStore& store, const std::string& job) {
  std::vector<uint32_t> first_rows;
  store.ForEachRowBlock(
      job, [&](StoredRowBlock b) { first_rows.push_back(b.block.first_row); }, nullptr);
  return first_rows;
}

TEST(RowBlockWriter, CheckpointsByBytesBeforeTheIntervalAndStoresEveryBlockInOrder) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("radflux_writer_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  auto store = JobStore::Open(dir.string());
  ASSERT_TRUE(store.ok()) << store.status();
  v1::Job job;
  job.set_job_id("writer-test");
  ASSERT_TRUE((*store)->CreateJob(job, /*request_hash=*/"").ok());
  constexpr uint32_t kBlockRows = 8;  // ~1.1 KB per block
  {
    RowBlockWriter writer(**store, job.job_id(), kBlockRows, /*interval_seconds=*/3600,
                          /*max_group_bytes=*/2048);
    for (uint32_t b = 0; b < 4; ++b) writer.Put(MakeBlock(b * kBlockRows, kBlockRows));
    // The interval is an hour away: only the byte cap can have stored these.
    std::vector<uint32_t> stored;
    for (int wait = 0; wait < 400 && stored.size() < 2; ++wait) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      stored = StoredFirstRows(**store, job.job_id());
    }
    EXPECT_GE(stored.size(), 2u) << "no checkpoint although the queue passed max_group_bytes";
    for (uint32_t b = 4; b < 10; ++b) writer.Put(MakeBlock(b * kBlockRows, kBlockRows));
  }  // destruction drains
  std::vector<uint32_t> expected;
  for (uint32_t b = 0; b < 10; ++b) expected.push_back(b * kBlockRows);
  EXPECT_EQ(StoredFirstRows(**store, job.job_id()), expected);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace radflux
