// One evaluation of stiffen's objective: the grid shell's frame assembled and solved
// (solver/block_cholesky.h, its analysis kept as in the stage, on two threads where there are
// two) and the adjoint compliance gradient (problems/grid_frame.h), on square quad grids of about
// the Great Court's sizes at h = 3 m (~900 nodes), h = 1.25 m (~5,000 nodes) and h = 1 m
// (~10,000 nodes). The stage needs 100–250 of these (benchmarks/RESULTS.md, "Stiffen").
#include <benchmark/benchmark.h>

#include <cmath>

#include "problems/grid_frame.h"
#include "solver/block_cholesky.h"

namespace pqlayout {
namespace {

// n × n quads, 2 m grid on a shallow dome, boundary pinned.
struct Grid {
  PolyMesh mesh;
  std::vector<Restraints> restraints;
};

Grid DomeGrid(int n) {
  Grid g;
  std::vector<VertexHandle> v;
  const double half = n / 2.0;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = 2.0 * (i - half), y = 2.0 * (j - half);
      v.push_back(g.mesh.add_vertex({x, y, 0.3 * 2.0 * half * (1.0 - (x * x + y * y) / (8.0 * half * half))}));
      const bool boundary = i == 0 || j == 0 || i == n || j == n;
      g.restraints.push_back(boundary ? Restraints{true, true, true, false, false, false} : Restraints{});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int k = j * (n + 1) + i;
      g.mesh.add_face(std::vector<VertexHandle>{v[k], v[k + 1], v[k + n + 2], v[k + n + 1]});
    }
  return g;
}

void BM_ComplianceAndGradient(benchmark::State& state) {
  const Grid g = DomeGrid(static_cast<int>(state.range(0)));
  const AnalysisOptions analysis;
  FrameWorkspace solver;
  GridCompliance c;
  for (auto _ : state)
    if (!EvaluateGridCompliance(g.mesh, g.restraints, analysis, true, &c, &solver).ok())
      state.SkipWithError("frame solve failed");
  state.counters["nodes"] = g.mesh.n_vertices();
  state.counters["members"] = g.mesh.n_edges();
}
BENCHMARK(BM_ComplianceAndGradient)->Arg(30)->Arg(70)->Arg(100)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace pqlayout
