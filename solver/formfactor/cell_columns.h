// CellColumns: the emitter columns F_cj of the direct-light cells (cell_direct.h), as the
// group rows drew them (monte_carlo: LightSampler::AddGroupEmitterColumns), kept so that the
// push-down after the solve reads them instead of casting the same seeded samples again.
// A cell's columns are kept with the (seed, budget) they were drawn with; the push-down takes
// them only for its own, and draws again (and keeps) the cells it does not find (rows built by
// remote workers, or read back from disk): the samples are seeded, so either way it gets the
// same numbers, bit for bit.
#pragma once

#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

namespace radflux {

// One emitter column of a cell: emitter unknown j and F_cj, the sum of its light samples'
// estimates in the order they were cast (the first sample that reached j first).
struct CellColumn {
  uint32_t emitter = 0;
  double form_factor = 0;
};

// Adds v > 0 to column j of `columns` (appended when new; non-positive v is ignored): the
// rule of RowAccumulator::Add, on a list as short as the emitters a cell's samples reach.
inline void AddCellColumn(std::vector<CellColumn>& columns, uint32_t j, double v) {
  if (!(v > 0)) return;
  for (CellColumn& c : columns) {
    if (c.emitter == j) {
      c.form_factor += v;
      return;
    }
  }
  columns.push_back({j, v});
}

class CellColumnCache {
 public:
  explicit CellColumnCache(size_t cells = 0) : cells_(cells) {}

  // Keeps cell c's columns, drawn with (seed, budget), unless the cell was kept before: the
  // first row to keep it wins. A group's row can be built twice at once (a server's backup of
  // a worker's block while that worker's rows are checked by recomputing some), and both
  // draw the same numbers; the claim keeps the second from writing under the first.
  // Thread-safe for distinct and equal cells alike; Find only after the rows are built.
  void Keep(uint32_t c, uint64_t seed, int budget, std::span<const CellColumn> columns) {
    if (c >= cells_.size()) return;
    Entry& e = cells_[c];
    if (e.claimed.exchange(true, std::memory_order_acq_rel)) return;
    e.columns.assign(columns.begin(), columns.end());
    e.seed = seed;
    e.budget = budget;
    e.kept = true;
  }
  // Cell c's columns if kept for (seed, budget); else null.
  const std::vector<CellColumn>* Find(uint32_t c, uint64_t seed, int budget) const {
    if (c >= cells_.size()) return nullptr;
    const Entry& e = cells_[c];
    return e.kept && e.seed == seed && e.budget == budget ? &e.columns : nullptr;
  }

 private:
  struct Entry {
    std::vector<CellColumn> columns;
    uint64_t seed = 0;
    int budget = 0;
    std::atomic<bool> claimed{false};  // a Keep has begun
    bool kept = false;
  };
  std::vector<Entry> cells_;
};

}  // namespace radflux
