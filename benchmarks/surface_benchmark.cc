// Reference-surface construction: generation (CGAL quality mesher + lift) and the
// SurfaceModel's cached quantities, at Great Court resolutions.
#include <benchmark/benchmark.h>

#include "geometry/surface_generators.h"
#include "geometry/surface_model.h"

namespace pqlayout {
namespace {

// Argument: edge length in centimetres.
void BM_GenerateGreatCourt(benchmark::State& state) {
  GeneratorParams params;
  params.name = "great_court";
  params.edge_length = state.range(0) / 100.0;
  size_t faces = 0;
  for (auto _ : state) {
    TriMesh mesh;
    if (!GenerateSurface(params, &mesh).ok()) state.SkipWithError("generation failed");
    faces = mesh.n_faces();
  }
  state.counters["faces"] = static_cast<double>(faces);
}
BENCHMARK(BM_GenerateGreatCourt)->Arg(200)->Arg(100)->Arg(50)->Unit(benchmark::kMillisecond);

void BM_SurfaceModel(benchmark::State& state) {
  GeneratorParams params;
  params.name = "great_court";
  params.edge_length = state.range(0) / 100.0;
  TriMesh mesh;
  if (!GenerateSurface(params, &mesh).ok()) state.SkipWithError("generation failed");
  for (auto _ : state) {
    SurfaceModel model(mesh);
    benchmark::DoNotOptimize(model.total_area());
  }
  state.counters["faces"] = static_cast<double>(mesh.n_faces());
}
BENCHMARK(BM_SurfaceModel)->Arg(100)->Arg(50)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace pqlayout
