// The 12-DOF Euler–Bernoulli beam element of the frame model (SPEC §7), templated on the
// scalar so that the same code gives the stiffness (double) and its derivatives with
// respect to the end positions and the section orientation (ceres::Jet, for the compliance
// gradient of `stiffen`, problems/grid_frame.h). DOFs per end: u_x, u_y, u_z, θ_x, θ_y, θ_z.
//   local x = (b − a)/L; local z = up projected normal to x, normalised; local y = z × x;
//   K_world = Tᵀ k(L) T with T = diag(R, R, R, R), R's rows the local axes.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace pqlayout {

// Cross-section constants (metres).
struct FrameSection {
  double area = 0.0;      // A
  double inertia_y = 0.0; // I about local y: bending with deflection along local z
  double inertia_z = 0.0; // I about local z: bending with deflection along local y
  double torsion = 0.0;   // J
  // Circular hollow section, outside diameter D, wall t: A = π/4 (D² − d²),
  // I = π/64 (D⁴ − d⁴) about both axes, J = 2I, d = D − 2t.
  static FrameSection CircularHollow(double diameter, double thickness);
  // Rectangular hollow section, width b (local y), height h (local z), wall t; thin-walled
  // torsion constant J = 2 t (b − t)² (h − t)² / (b + h − 2t) (Bredt).
  static FrameSection RectangularHollow(double width, double height, double thickness);
};

struct FrameMaterial {
  double youngs_modulus = 210e9;  // E, Pa
  double shear_modulus = 210e9 / 2.6;  // G = E / (2(1+ν)), Pa
};

template <typename T>
using Matrix12 = Eigen::Matrix<T, 12, 12>;

// The 12×12 local stiffness matrix of one member (local axes, DOFs [a(6), b(6)]).
template <typename T>
Matrix12<T> LocalBeamStiffness(const T& L, const FrameSection& s, const FrameMaterial& m) {
  const double E = m.youngs_modulus, G = m.shear_modulus;
  const T EA = E * s.area / L, GJ = G * s.torsion / L;
  const double Iz = s.inertia_z, Iy = s.inertia_y;
  Matrix12<T> k = Matrix12<T>::Zero();
  // Axial (0, 6) and torsion (3, 9).
  k(0, 0) = k(6, 6) = EA;
  k(0, 6) = k(6, 0) = -EA;
  k(3, 3) = k(9, 9) = GJ;
  k(3, 9) = k(9, 3) = -GJ;
  // Bending in the x–y plane (v: 1, 7; θ_z: 5, 11), stiffness E I_z.
  const T a = 12 * E * Iz / (L * L * L), b = 6 * E * Iz / (L * L), c = 4 * E * Iz / L, d = 2 * E * Iz / L;
  k(1, 1) = k(7, 7) = a;
  k(1, 7) = k(7, 1) = -a;
  k(1, 5) = k(5, 1) = k(1, 11) = k(11, 1) = b;
  k(7, 5) = k(5, 7) = k(7, 11) = k(11, 7) = -b;
  k(5, 5) = k(11, 11) = c;
  k(5, 11) = k(11, 5) = d;
  // Bending in the x–z plane (w: 2, 8; θ_y: 4, 10), stiffness E I_y (signs flip: θ_y = −dw/dx).
  const T e = 12 * E * Iy / (L * L * L), f = 6 * E * Iy / (L * L), g = 4 * E * Iy / L, h = 2 * E * Iy / L;
  k(2, 2) = k(8, 8) = e;
  k(2, 8) = k(8, 2) = -e;
  k(2, 4) = k(4, 2) = k(2, 10) = k(10, 2) = -f;
  k(8, 4) = k(4, 8) = k(8, 10) = k(10, 8) = f;
  k(4, 4) = k(10, 10) = g;
  k(4, 10) = k(10, 4) = h;
  return k;
}

// The consistent geometric stiffness of one member under axial force N (tension positive),
// local axes, DOFs [a(6), b(6)] (McGuire, Gallagher & Ziemian, Matrix Structural Analysis,
// 2nd ed., eq. 9.19, without the end-moment terms): k_G = N/L ×
//   axial      [1, −1; −1, 1]                                        (u: 0, 6)
//   x–y plane  [6/5, L/10, −6/5, L/10; ·, 2L²/15, −L/10, −L²/30; ·, ·, 6/5, −L/10; ·, ·, ·, 2L²/15]
//              over (v_a, θz_a, v_b, θz_b); x–z plane the same over (w, θ_y) with the signs of
//              the L/10 terms flipped (θ_y = −dw/dx, as in LocalBeamStiffness)
//   torsion    I_p/A [1, −1; −1, 1], I_p = I_y + I_z                   (θ_x: 3, 9)
// The buckling factors λ solve (K + λ K_G(N)) φ = 0 (solver/frame_buckling.h).
inline Matrix12<double> LocalGeometricStiffness(double L, double N, const FrameSection& s) {
  Matrix12<double> k = Matrix12<double>::Zero();
  const double c = N / L, ip = (s.inertia_y + s.inertia_z) / s.area;
  k(0, 0) = k(6, 6) = c, k(0, 6) = k(6, 0) = -c;
  k(3, 3) = k(9, 9) = c * ip, k(3, 9) = k(9, 3) = -c * ip;
  const double a = 1.2 * c, b = c * L / 10.0, d = c * 2.0 * L * L / 15.0, e = -c * L * L / 30.0;
  // x–y plane: v (1, 7), θ_z (5, 11).
  k(1, 1) = k(7, 7) = a, k(1, 7) = k(7, 1) = -a;
  k(1, 5) = k(5, 1) = k(1, 11) = k(11, 1) = b;
  k(7, 5) = k(5, 7) = k(7, 11) = k(11, 7) = -b;
  k(5, 5) = k(11, 11) = d, k(5, 11) = k(11, 5) = e;
  // x–z plane: w (2, 8), θ_y (4, 10).
  k(2, 2) = k(8, 8) = a, k(2, 8) = k(8, 2) = -a;
  k(2, 4) = k(4, 2) = k(2, 10) = k(10, 2) = -b;
  k(8, 4) = k(4, 8) = k(8, 10) = k(10, 8) = b;
  k(4, 4) = k(10, 10) = d, k(4, 10) = k(10, 4) = e;
  return k;
}

// Rows: local x, y, z axes in world coordinates. `up` need not be unit length.
template <typename T>
Eigen::Matrix<T, 3, 3> MemberFrame(const Eigen::Matrix<T, 3, 1>& a, const Eigen::Matrix<T, 3, 1>& b,
                                   const Eigen::Matrix<T, 3, 1>& up) {
  using std::abs;
  using Vector = Eigen::Matrix<T, 3, 1>;
  const Vector x = (b - a).normalized();
  Vector z = up - x * x.dot(up);
  if (z.norm() < 1e-9 * up.norm() || !(z.norm() > T(0.0))) {
    // The reference is parallel to the member: any perpendicular will do.
    const Vector trial = abs(x.z()) < T(0.9) ? Vector::UnitZ() : Vector::UnitX();
    z = trial - x * x.dot(trial);
  }
  z.normalize();
  const Vector y = z.cross(x);
  Eigen::Matrix<T, 3, 3> R;
  R.row(0) = x;
  R.row(1) = y;
  R.row(2) = z;
  return R;
}

// The member's stiffness in world coordinates, K = Tᵀ k T.
template <typename T>
Matrix12<T> WorldBeamStiffness(const Eigen::Matrix<T, 3, 1>& a, const Eigen::Matrix<T, 3, 1>& b,
                               const Eigen::Matrix<T, 3, 1>& up, const FrameSection& s, const FrameMaterial& m) {
  const Eigen::Matrix<T, 3, 3> R = MemberFrame<T>(a, b, up);
  Matrix12<T> Tm = Matrix12<T>::Zero();
  for (int k = 0; k < 4; ++k) Tm.template block<3, 3>(3 * k, 3 * k) = R;
  return Tm.transpose() * LocalBeamStiffness<T>((b - a).norm(), s, m) * Tm;
}

// uᵀ K u for the member's world DOFs u (twice its strain energy), from the local DOFs
// l = T u (four 3×3 rotations) in closed form, the quadratic forms of LocalBeamStiffness:
//   EA/L (l₆ − l₀)² + GJ/L (l₉ − l₃)²
//   + E I_z/L³ [12 (l₁ − l₇)² + 12 L (l₁ − l₇)(l₅ + l₁₁) + 4 L² (l₅² + l₅ l₁₁ + l₁₁²)]
//   + E I_y/L³ [12 (l₂ − l₈)² − 12 L (l₂ − l₈)(l₄ + l₁₀) + 4 L² (l₄² + l₄ l₁₀ + l₁₀²)]
// For the per-member autodiff of the compliance gradient: a Jet evaluation of
// WorldBeamStiffness costs ~100× more (tests/stiffen_test.cc checks the two agree).
template <typename T>
T BeamEnergyTwice(const Eigen::Matrix<T, 3, 1>& a, const Eigen::Matrix<T, 3, 1>& b, const Eigen::Matrix<T, 3, 1>& up,
                  const Eigen::Matrix<double, 12, 1>& u, const FrameSection& s, const FrameMaterial& m) {
  const Eigen::Matrix<T, 3, 3> R = MemberFrame<T>(a, b, up);
  Eigen::Matrix<T, 12, 1> l;
  for (int k = 0; k < 4; ++k) l.template segment<3>(3 * k) = R * u.segment<3>(3 * k).template cast<T>();
  const T L = (b - a).norm();
  const double E = m.youngs_modulus, G = m.shear_modulus;
  const T axial = l[6] - l[0], twist = l[9] - l[3], v = l[1] - l[7], w = l[2] - l[8];
  const T bend_z = T(12.0) * v * v + T(12.0) * L * v * (l[5] + l[11]) + T(4.0) * L * L * (l[5] * l[5] + l[5] * l[11] + l[11] * l[11]);
  const T bend_y = T(12.0) * w * w - T(12.0) * L * w * (l[4] + l[10]) + T(4.0) * L * L * (l[4] * l[4] + l[4] * l[10] + l[10] * l[10]);
  return E * s.area / L * axial * axial + G * s.torsion / L * twist * twist +
         E * s.inertia_z / (L * L * L) * bend_z + E * s.inertia_y / (L * L * L) * bend_y;
}

}  // namespace pqlayout
