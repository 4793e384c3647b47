// Southwell progressive refinement (Cohen et al. 1988). B and the unshot radiosity dB
// keep the invariant B = E + rho F (B - dB): shooting patch i adds rho_j F_ji dB_i to
// every j, read from column i of F (the receivers' own rows, kept as F^T). Cohen et al.
// use row i through reciprocity (F_ji = A_i F_ij / A_j) instead; with sampled rows that
// are not exactly reciprocal that solves a different system, and it spreads a light's
// direct illumination by the light's own few rays rather than by each receiver's
// accurate emitter column, so radflux shoots through columns and converges to the same
// B as the gathering methods. Each iteration shoots a batch: the patches with
// the most unshot power A_i |dB_i| (summed over lanes, each relative to its emitted
// power), shot together and scattered in parallel over fixed blocks of receivers, each
// receiver summing its shooters in batch order (same result on any thread count).
// The budget and the stopping test count sweep-equivalents: batches until they shot as
// many entries as the rows hold (a sweep's work), then the true residual measure of B
// (one SpMV) decides, as for every other method.
#include <algorithm>
#include <cmath>

#include "solver/solve/methods.h"
#include "solver/solve/stopping.h"

namespace radflux {
namespace {

// Shooters per batch: grows with n so a batch outweighs the O(n) selection; fixed by n
// alone (never by threads) so that results are bit-identical on any thread count.
size_t BatchSize(uint32_t n) { return std::clamp<size_t>(n / 128, 1, 256); }

struct ShootState {
  std::vector<Rgb> db;        // unshot radiosity per lane
  std::vector<double> power;  // selection key per patch
  Rgb emitted{};              // sum_i A_i E_i per lane
  CsrMatrix columns;          // F^T: row i lists (j, F_ji), what shooting i needs
};

// Recomputes the selection keys; returns the unshot fraction, unshot power over emitted
// power (max over lanes).
double Measure(const BandSystem& bands, ShootState& st) {
  const std::vector<double>& area = *bands.area;
  const Rgb unshot =
      ReduceBlocks(bands.n, kVectorBlock, bands.threads, [&](int64_t begin, int64_t end) {
        Rgb s{};
        for (int64_t i = begin; i < end; ++i) {
          double key = 0;
          for (int k = 0; k < bands.lanes; ++k) {
            s[k] += area[i] * std::abs(st.db[i][k]);
            key += area[i] * std::abs(st.db[i][k]) / st.emitted[k];
          }
          st.power[i] = key;
        }
        return s;
      });
  double fraction = 0;
  for (int k = 0; k < bands.lanes; ++k) fraction = std::max(fraction, unshot[k] / st.emitted[k]);
  return fraction;
}

// The up-to-m patches with the largest key (ties: lower index), best first.
std::vector<uint32_t> SelectBatch(const std::vector<double>& power, size_t m) {
  const auto better = [&](uint32_t a, uint32_t b) {
    return power[a] > power[b] || (power[a] == power[b] && a < b);
  };
  std::vector<uint32_t> heap;  // front = worst kept
  for (uint32_t i = 0; i < power.size(); ++i) {
    if (!(power[i] > 0)) continue;
    if (heap.size() < m) {
      heap.push_back(i);
      std::push_heap(heap.begin(), heap.end(), better);
    } else if (better(i, heap.front())) {
      std::pop_heap(heap.begin(), heap.end(), better);
      heap.back() = i;
      std::push_heap(heap.begin(), heap.end(), better);
    }
  }
  std::sort(heap.begin(), heap.end(), better);
  return heap;
}

// Shoots `batch` (their dB taken before any of them receives).
void ShootBatch(const BandSystem& bands, const std::vector<uint32_t>& batch, ShootState& st,
                std::vector<Rgb>& b) {
  std::vector<Rgb> shot(batch.size());
  for (size_t s = 0; s < batch.size(); ++s) {
    shot[s] = st.db[batch[s]];
    st.db[batch[s]] = Rgb{};
  }
  ParallelFor(bands.n, kVectorBlock, bands.threads, [&](int64_t begin, int64_t end) {
    for (size_t s = 0; s < batch.size(); ++s) {
      const uint32_t i = batch[s];
      const auto cols = st.columns.RowCols(i);
      const auto values = st.columns.RowValues(i);
      size_t e = static_cast<size_t>(
          std::lower_bound(cols.begin(), cols.end(), static_cast<uint32_t>(begin)) - cols.begin());
      for (; e < cols.size() && cols[e] < end; ++e) {
        const uint32_t j = cols[e];
        for (int k = 0; k < bands.lanes; ++k) {
          const double delta = bands.rho[j][k] * values[e] * shot[s][k];
          b[j][k] += delta;
          st.db[j][k] += delta;
        }
      }
    }
  });
}

// B plus the ambient term rho_i * sum(A dB) / (A_total (1 - rho_avg)) per lane.
std::vector<Rgb> WithAmbient(const BandSystem& bands, const ShootState& st,
                             const std::vector<Rgb>& b) {
  const std::vector<double>& area = *bands.area;
  Rgb unshot{}, rho_area{}, ambient{};
  for (uint32_t i = 0; i < bands.n; ++i)
    for (int k = 0; k < bands.lanes; ++k) {
      unshot[k] += area[i] * st.db[i][k];
      rho_area[k] += area[i] * bands.rho[i][k];
    }
  for (int k = 0; k < bands.lanes; ++k) {
    const double rho_avg = rho_area[k] / bands.total_area;
    ambient[k] = rho_avg < 1 ? unshot[k] / (bands.total_area * (1 - rho_avg)) : 0;
  }
  std::vector<Rgb> display = b;
  for (uint32_t i = 0; i < bands.n; ++i)
    for (int k = 0; k < bands.lanes; ++k) display[i][k] += bands.rho[i][k] * ambient[k];
  return display;
}

// The shooting state for B = b: from its residual, or (resume) from the unshot radiosity
// saved with b, in which case shooting continues exactly where it stopped.
ShootState StartShooting(const BandSystem& bands, const std::vector<Rgb>* unshot,
                         std::vector<Rgb>& b) {
  ShootState st;
  if (unshot != nullptr) {
    st.db = PackLanes(bands, *unshot);
  } else {
    ResidentLaneResiduals(bands, b, &st.db);  // dB = r(B0); B = B0 + r keeps the invariant
  }
  for (uint32_t i = 0; i < bands.n; ++i)
    for (int k = 0; k < bands.lanes; ++k) {
      if (unshot == nullptr) b[i][k] += st.db[i][k];
      st.emitted[k] += (*bands.area)[i] * std::abs(bands.emission[i][k]);
    }
  st.power.assign(bands.n, 0);
  st.columns = bands.f->Transposed();
  return st;
}

}  // namespace

absl::Status SolveSouthwell(const BandSystem& bands, const SolverOptions& options,
                            const SolveCallback& callback, std::vector<Rgb>& b,
                            SolveResult& result) {
  ShootState st = StartShooting(bands, options.initial_unshot, b);
  double fraction = Measure(bands, st);
  IterationMonitor monitor(bands, options, callback, result);
  monitor.SetShootingState(&b, &st.db);
  const size_t m = BatchSize(bands.n);
  const uint64_t sweep_entries = std::max<uint64_t>(1, st.columns.nnz());
  while (!monitor.ShouldStop()) {
    // One sweep-equivalent: batches until they shot as many entries as the rows hold.
    for (uint64_t shot = 0; shot < sweep_entries;) {
      const std::vector<uint32_t> batch = SelectBatch(st.power, m);
      if (batch.empty()) break;  // nothing left to shoot
      for (uint32_t i : batch) shot += 1 + st.columns.RowCols(i).size();
      ShootBatch(bands, batch, st, b);
      fraction = Measure(bands, st);
    }
    const double residual = MaxOverLanes(bands, ResidentLaneResiduals(bands, b, nullptr));
    const bool snapshot = monitor.SnapshotDue();
    const bool done =
        monitor.Record(residual, residual, fraction, snapshot ? WithAmbient(bands, st, b) : b);
    if (done) break;
  }
  result.unshot_fraction = fraction;
  return absl::OkStatus();
}

}  // namespace radflux
