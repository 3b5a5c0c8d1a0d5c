// Numerics: one place that fixes how this process computes, so that a run gives the same
// answer on every machine.
//
// Decisions (README, "Same answer on every machine"):
// - One BLAS/LAPACK, linked on purpose: OpenBLAS (CMake's BLA_VENDOR=OpenBLAS), linked
//   before every other library so that each BLAS and LAPACK symbol (CHOLMOD's, Ceres') binds
//   to it, never to ATLAS, which Debian's Ceres also pulls in.
// - No CPU-dispatched kernel decides a layout: OpenBLAS picks its kernels per CPU (AVX-512,
//   AVX2, SSE), and a factor that differs by one ulp sends a non-convex solve to another local
//   minimum. So with one thread CHOLMOD factors simplicially (no BLAS; cholmod_solver.h)
//   and Ceres always uses Eigen's sparse Cholesky (compiled code, no BLAS): no BLAS call
//   reaches the numbers in report.json, and scripts/check_reproducible.sh checks that every
//   output is byte-identical under each OpenBLAS kernel.
// - A fixed thread count (`threads`, default 1): Ceres sums per-thread partial costs and
//   gradients in an order that depends on scheduling, so only one thread gives bit-identical
//   runs; OpenBLAS and OpenMP (CHOLMOD) get the same count. More threads trade that for
//   speed: Ceres evaluates in parallel and CHOLMOD may factor supernodally on OpenBLAS.
#pragma once

#include <string>

namespace pqlayout {

// Sets the thread count of Ceres (through SparseCholeskyOptions), OpenBLAS and OpenMP for
// the rest of the process. threads >= 1.
void SetNumericThreads(int threads);
int NumericThreads();

// The BLAS this process runs on, as OpenBLAS reports it, e.g.
// "OpenBLAS 0.3.21 NO_LAPACKE DYNAMIC_ARCH NO_AFFINITY Haswell MAX_THREADS=64".
std::string BlasDescription();
// The kernel OpenBLAS chose for this CPU (or OPENBLAS_CORETYPE), e.g. "Haswell".
std::string BlasCore();

}  // namespace pqlayout
