// layout.density: panel_area (problems/panel_area.h) on known answers: for linear φ, ψ on a
// flat square the scale is 1/√(a b sin γ), the scaled layout's cells have area h² exactly,
// and the extracted mesh then has area / h² cells whatever the crossing angle.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/quad_extraction.h"
#include "problems/panel_area.h"
#include "tests/test_meshes.h"

namespace pqlayout {
namespace {

using testing::FlatGridSoup;
using testing::ToMesh;

// The square [0, 30]² in 1 m cells, two triangles each.
SurfaceModel Square() {
  PolygonSoup soup = FlatGridSoup(30);
  return SurfaceModel(ToMesh(soup));
}

// φ = a x / h, ψ = b (x cos γ + y sin γ) / h: lines a / h and b / h apart, crossing at γ.
void Linear(const SurfaceModel& s, double a, double b, double gamma, double h, std::vector<double>* phi,
            std::vector<double>* psi) {
  phi->clear();
  psi->clear();
  for (int v = 0; v < s.num_vertices(); ++v) {
    const Eigen::Vector3d p = s.position(v);
    phi->push_back(a * p.x() / h);
    psi->push_back(b * (std::cos(gamma) * p.x() + std::sin(gamma) * p.y()) / h);
  }
}

TEST(PanelArea, ScaleOfLinearFieldsIsAnalytic) {
  PolygonSoup soup = FlatGridSoup(10);
  for (auto& p : soup.points) p *= 3.0;
  const SurfaceModel s(ToMesh(soup));
  const double h = 2.5;
  for (const auto& [a, b, gamma] : {std::tuple{1.0, 1.0, M_PI / 2}, std::tuple{1.0, 1.0, M_PI / 6},
                                     std::tuple{0.8, 1.3, 1.1}, std::tuple{2.0, 0.5, 2.5}}) {
    std::vector<double> phi, psi;
    Linear(s, a, b, gamma, h, &phi, &psi);
    EXPECT_NEAR(PanelAreaScale(s, phi, psi, h), 1.0 / std::sqrt(a * b * std::sin(gamma)), 1e-12)
        << "a " << a << " b " << b << " γ " << gamma;
    // Scaled, the fields have unit mean Jacobian: scaling again changes nothing.
    const double scale = PanelAreaScale(s, phi, psi, h);
    for (double& x : phi) x *= scale;
    for (double& x : psi) x *= scale;
    EXPECT_NEAR(PanelAreaScale(s, phi, psi, h), 1.0, 1e-12);
  }
  // Degenerate: ψ constant → no cells; the scale stays 1.
  std::vector<double> phi, psi;
  Linear(s, 1.0, 0.0, 1.0, h, &phi, &psi);
  EXPECT_EQ(PanelAreaScale(s, phi, psi, h), 1.0);
}

// Families crossing at 40° and 90°, spacing h = 1.5 m: unscaled the oblique grid has
// sin 40° = 0.64 times the cells of the orthogonal one; scaled to panel area h² both have
// about 900 / 2.25 = 400 whole cells plus the cut ones along the sides, (30 / 1.5 + 1)² = 441
// for the orthogonal grid (measured: unscaled 441 / 307, scaled 441 / 462).
TEST(PanelArea, ScaledLayoutsHaveEqualCellCounts) {
  const SurfaceModel s = Square();
  const double h = 1.5;
  std::vector<int> unscaled, scaled;
  for (const double gamma : {M_PI / 2, 40.0 * M_PI / 180.0}) {
    std::vector<double> phi, psi;
    Linear(s, 1.0, 1.0, gamma, h, &phi, &psi);
    for (double& x : phi) x += 0.31;
    for (double& x : psi) x += 0.17;
    ExtractedMesh plain;
    ASSERT_TRUE(ExtractQuadMesh(s, phi, psi, 30.0, 0.0, &plain, false).ok());
    unscaled.push_back(static_cast<int>(plain.mesh.n_faces()));
    const double k = PanelAreaScale(s, phi, psi, h);
    for (double& x : phi) x *= k;
    for (double& x : psi) x *= k;
    ExtractedMesh out;
    ASSERT_TRUE(ExtractQuadMesh(s, phi, psi, 30.0, 0.0, &out, false).ok());
    scaled.push_back(static_cast<int>(out.mesh.n_faces()));
  }
  std::cout << "cells, 90° / 40°: unscaled " << unscaled[0] << " / " << unscaled[1] << ", scaled " << scaled[0]
            << " / " << scaled[1] << "\n";
  EXPECT_LT(unscaled[1], 0.75 * unscaled[0]);
  EXPECT_EQ(scaled[0], 441);
  EXPECT_NEAR(scaled[1], 441.0, 0.1 * 441.0);
  EXPECT_NEAR(double(scaled[1]) / scaled[0], 1.0, 0.08);
}

}  // namespace
}  // namespace pqlayout
