// The 3D frame solver (assembly + CHOLMOD) on a square grid shell of about 5,000 nodes
// (issue 7: ≤ 1 s), and on larger grids for the growth; the linear buckling solve (issue 18:
// ≤ 1 s at ~900 nodes, ≤ 10 s at ~5,000), three factors as analyze's default.
#include <benchmark/benchmark.h>

#include "solver/frame_analysis.h"
#include "solver/frame_buckling.h"

namespace pqlayout {
namespace {

// n × n nodes, 2 m grid on a shallow dome, boundary pinned, 10 kN per node downwards.
FrameModel GridShell(int n) {
  FrameModel m;
  const double half = n - 1.0;
  auto id = [n](int i, int j) { return j * n + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = 2.0 * i - half, y = 2.0 * j - half;
      m.nodes.emplace_back(x, y, 0.3 * half * (1.0 - (x * x + y * y) / (2.0 * half * half)));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (i + 1 < n) m.members.push_back({id(i, j), id(i + 1, j), Eigen::Vector3d::UnitZ()});
      if (j + 1 < n) m.members.push_back({id(i, j), id(i, j + 1), Eigen::Vector3d::UnitZ()});
    }
  m.restraints.assign(m.nodes.size(), Restraints{});
  m.loads.assign(m.nodes.size(), NodeVector::Zero());
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (i == 0 || j == 0 || i == n - 1 || j == n - 1) m.restraints[id(i, j)] = {true, true, true, false, false, false};
      m.loads[id(i, j)][2] = -1e4;
    }
  m.section = FrameSection::CircularHollow(0.1143, 0.005);
  return m;
}

void BM_SolveFrame(benchmark::State& state) {
  const FrameModel m = GridShell(static_cast<int>(state.range(0)));
  FrameResult r;
  for (auto _ : state)
    if (!SolveFrame(m, &r).ok()) state.SkipWithError("frame solve failed");
  state.counters["nodes"] = m.nodes.size();
  state.counters["members"] = m.members.size();
}
BENCHMARK(BM_SolveFrame)->Arg(71)->Arg(141)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SolveBuckling(benchmark::State& state) {
  const FrameModel m = GridShell(static_cast<int>(state.range(0)));
  FrameResult r;
  if (!SolveFrame(m, &r).ok()) state.SkipWithError("frame solve failed");
  BucklingResult b;
  for (auto _ : state)
    if (!SolveBuckling(m, r, 3, &b).ok() || !b.buckles) state.SkipWithError("buckling solve failed");
  state.counters["nodes"] = m.nodes.size();
  state.counters["factor"] = b.factors.empty() ? 0.0 : b.factors.front();
  state.counters["solves"] = b.operations;
}
BENCHMARK(BM_SolveBuckling)->Arg(31)->Arg(71)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace pqlayout
