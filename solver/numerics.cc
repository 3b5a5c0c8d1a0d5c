#include "solver/numerics.h"

#include <algorithm>
#include <atomic>

// OpenBLAS' own entry points (cblas.h of libopenblas-dev declares them; declared here so
// that no other BLAS's cblas.h can be picked up instead) and OpenMP's.
extern "C" {
char* openblas_get_config(void);
char* openblas_get_corename(void);
void openblas_set_num_threads(int num_threads);
void omp_set_num_threads(int num_threads);
}

namespace pqlayout {
namespace {
std::atomic<int> g_threads{1};
}  // namespace

void SetNumericThreads(int threads) {
  threads = std::max(1, threads);
  g_threads = threads;
  openblas_set_num_threads(threads);
  omp_set_num_threads(threads);
}

int NumericThreads() { return g_threads; }

std::string BlasDescription() {
  const char* config = openblas_get_config();
  return config ? config : "OpenBLAS (unknown configuration)";
}

std::string BlasCore() {
  const char* core = openblas_get_corename();
  return core ? core : "unknown";
}

}  // namespace pqlayout
