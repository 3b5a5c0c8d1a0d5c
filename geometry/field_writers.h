// Per-element fields on the reference surface, written for ParaView (legacy VTK polydata,
// binary, double precision) and as CSV tables.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "base/status.h"
#include "geometry/surface_model.h"

namespace pqlayout {

struct SurfaceFields {
  std::vector<std::pair<std::string, std::vector<double>>> vertex_scalars;
  std::vector<std::pair<std::string, std::vector<Eigen::Vector3d>>> vertex_vectors;
  std::vector<std::pair<std::string, std::vector<double>>> face_scalars;
  std::vector<std::pair<std::string, std::vector<Eigen::Vector3d>>> face_vectors;
};

// Writes the surface and its fields as a legacy VTK file (opens in ParaView), atomically.
// origin is added to every point (a georeferenced surface is solved in a local frame).
// BINARY (the headers are text, the data big-endian doubles and 32-bit ints, as the legacy
// format defines them): every double exact, ~40 % of the ASCII file's size, and written
// ~10× faster (at a million triangles the ASCII file was 161 MB and most of the guidance
// stage's 2.8 s of field writing).
Status WriteFieldsVtk(const SurfaceModel& surface, const SurfaceFields& fields, const std::string& path,
                      const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());
// The same from the surface's points (origin already added) and triangles: what a writer on
// another thread holds as its own copy (base/background_writer.h).
Status WriteFieldsVtk(const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<int, 3>>& triangles,
                      const SurfaceFields& fields, const std::string& path);

// A CSV table: header row of column names, then one row per element with its id first.
// Each column is a vector of values of the same length; vector-valued columns are split
// into three named columns by the caller.
Status WriteCsvTable(const std::vector<std::string>& header, const std::vector<const std::vector<double>*>& columns,
                     const std::string& path);

}  // namespace pqlayout
