// The dense kernel of the multifrontal factor (solver/supernodal_cholesky.h): the partial
// Cholesky factorisation of one frontal matrix, right-looking in panels of kPanel columns.
//
// Every sum runs in an order fixed by this code — over the panel's columns in turn, a panel's
// products accumulated from zero and subtracted once — and the 4 × 4 blocks use Eigen's
// fixed-size code, compiled once with the program's flags: no CPU dispatch and no blocking by
// cache size, so the same bits on every machine (solver/numerics.h). Only the lower triangle
// of a front is read; the diagonal 4 × 4 blocks also write above it, which nothing reads.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <Eigen/Core>

namespace pqlayout {
namespace front_kernels {

constexpr int kPanel = 32;

// F(r, c) −= Σ_{p0 ≤ p < p1} F(r, p) F(c, p) for every column c ≥ c0 and row r ≥ c of the
// m × m column-major F.
inline void UpdateTrailing(double* F, int m, int p0, int p1, int c0) {
  using Block = Eigen::Map<Eigen::Matrix4d, Eigen::Unaligned, Eigen::OuterStride<>>;
  for (int c = c0; c < m; c += 4) {
    const int nc = std::min(4, m - c);
    for (int r = c; r < m; r += 4) {
      const int nr = std::min(4, m - r);
      if (nr == 4 && nc == 4) {
        Eigen::Matrix4d sum = Eigen::Matrix4d::Zero();
        for (int p = p0; p < p1; ++p) {
          const double* column = F + static_cast<std::ptrdiff_t>(p) * m;
          sum.noalias() += Eigen::Map<const Eigen::Vector4d>(column + r) * Eigen::Map<const Eigen::RowVector4d>(column + c);
        }
        Block(F + static_cast<std::ptrdiff_t>(c) * m + r, Eigen::OuterStride<>(m)) -= sum;
        continue;
      }
      for (int j = 0; j < nc; ++j)
        for (int i = 0; i < nr; ++i) {
          double sum = 0.0;
          for (int p = p0; p < p1; ++p) {
            const double* column = F + static_cast<std::ptrdiff_t>(p) * m;
            sum += column[r + i] * column[c + j];
          }
          F[static_cast<std::ptrdiff_t>(c + j) * m + r + i] -= sum;
        }
    }
  }
}

// Columns p0 … p1 − 1 of F (every earlier panel already applied to them), left-looking within
// the panel: each column gets the panel's earlier columns subtracted, its pivot's root and the
// division. Returns −1, or the column whose pivot is not positive (or not finite).
inline int FactorPanel(double* F, int m, int p0, int p1) {
  for (int j = p0; j < p1; ++j) {
    double* target = F + static_cast<std::ptrdiff_t>(j) * m;
    for (int q = p0; q < j; ++q) {
      const double* source = F + static_cast<std::ptrdiff_t>(q) * m;
      const double scale = source[j];
      for (int i = j; i < m; ++i) target[i] -= source[i] * scale;
    }
    const double pivot = target[j];
    if (!(pivot > 0.0) || !std::isfinite(pivot)) return j;
    const double root = std::sqrt(pivot);
    target[j] = root;
    for (int i = j + 1; i < m; ++i) target[i] /= root;
  }
  return -1;
}

// Factors the first k of F's m columns in place: L11 L11ᵀ = F11, L21 = F21 L11⁻ᵀ, and
// F22 ← F22 − L21 L21ᵀ (the update matrix passed to the parent). Returns −1, or the column
// (< k) whose pivot is not positive.
inline int FactorFront(double* F, int m, int k) {
  for (int p0 = 0; p0 < k; p0 += kPanel) {
    const int p1 = std::min(k, p0 + kPanel);
    if (const int failed = FactorPanel(F, m, p0, p1); failed >= 0) return failed;
    UpdateTrailing(F, m, p0, p1, p1);
  }
  return -1;
}

}  // namespace front_kernels
}  // namespace pqlayout
