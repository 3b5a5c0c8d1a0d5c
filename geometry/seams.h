// Seams (branch cuts) for level-set layouts: the surface cut open along vertex paths, so that
// the level-set functions φ, ψ may jump across them.
//
// Why. A single-valued function cannot follow a guidance line field everywhere:
// - around a singularity of index ±½ (an umbilic of the curvature field, a trisector of the
//   strain field) the line field turns by ±π, while the level lines of a function turn by a
//   multiple of 2π; and
// - around a hole (the Reading Room of the Great Court) level lines that run radially need a
//   function that grows by a whole number of levels once round.
// A single-valued φ hides the mismatch in a band of misaligned or crowded level lines. A
// seam moves it onto a curve: across the seam φ₊ = s·φ₋ + a with s = ±1 and a an integer
// number of levels, so the level lines φ = i meet the level lines φ = s·i + a on the other
// side and the layout is seamless; at a ±½ singularity (s = −1) the quad mesh then has an
// irregular vertex, as in the paper's curvature reference (Fig. 8b, "branch points";
// Kälberer, Nieser & Polthier 2007, QuadCover).
//
// This file does the topology only: routing the seams (RouteSeams) and cutting the mesh open
// (SeamCut). The transitions (s, a) are the level-set stage's business.
#pragma once

#include <memory>
#include <vector>

#include "base/status.h"
#include "geometry/surface_model.h"

namespace pqlayout {

// Seam paths for `surface` (vertex chains, see SeamCut::Build): one from every tip (an
// interior vertex, e.g. a line-field singularity) to the boundary, then one joining every
// boundary loop but the outer one to the loops already joined (so the cut surface is a
// disc if the surface is a disc with holes). Shortest paths in the edge graph with edge cost
// length × (floor + mean face_weight of the edge's faces): seams run where alignment matters
// least. Paths do not touch each other, other tips or the boundary except at their ends; a
// tip with no such path to the boundary is skipped (tips on the boundary too).
std::vector<std::vector<int>> RouteSeams(const SurfaceModel& surface, const std::vector<double>& face_weight,
                                         const std::vector<int>& tips, double floor = 0.05);

// ∫ w ds along a path (w: the mean face_weight of each edge's faces): how much weighted
// length a hidden branch cut along it would misalign.
double PathWeight(const SurfaceModel& surface, const std::vector<double>& face_weight, const std::vector<int>& path);

// One edge of a seam, between face `minus` (left of the path's direction, seen from the
// normal) and face `plus`.
struct SeamEdge {
  int path = -1;
  int original_edge = -1;            // edge of the original surface
  int minus_face = -1, plus_face = -1;
  int cut_edge_minus = -1, cut_edge_plus = -1;  // the two boundary edges of the cut surface
};

// A vertex of a seam seen from both sides: the cut vertex the minus side uses and the one the
// plus side uses (the same at a path's interior tip, where the seam ends inside the surface).
struct SeamCopyPair {
  int path = -1;
  int original_vertex = -1;
  int minus = -1, plus = -1;  // cut vertices
};

class SeamCut {
 public:
  // paths: chains of adjacent vertices of `surface`; each ends at a boundary vertex, starts at
  // a boundary vertex or an interior tip, and has only interior vertices in between; no
  // vertex belongs to two paths. InvalidInput otherwise.
  static Status Build(const SurfaceModel& surface, std::vector<std::vector<int>> paths,
                      std::unique_ptr<SeamCut>* out);

  // The surface cut open: the same faces (same indices, same corner order), every vertex
  // duplicated once per fan of faces that the seams separate at it. Seam edges are boundary
  // edges of the cut surface (use is_seam_edge to tell them from the real boundary).
  const SurfaceModel& cut() const { return *cut_; }
  int num_paths() const { return static_cast<int>(paths_.size()); }
  const std::vector<int>& path(int p) const { return paths_[p]; }
  // Whether path p starts at an interior tip (a branch point) rather than on the boundary.
  bool starts_inside(int p) const { return starts_inside_[p]; }
  // Where vertex v of the original surface is (its first copy's position).
  Eigen::Vector3d position(int original_vertex) const { return cut_->position(first_copy_[original_vertex]); }
  int original_vertex(int cut_vertex) const { return original_vertex_[cut_vertex]; }
  // The seam path a cut edge lies on, or −1.
  int seam_path_of_cut_edge(int cut_edge) const { return seam_of_cut_edge_[cut_edge]; }
  bool is_seam_edge(int cut_edge) const { return seam_of_cut_edge_[cut_edge] >= 0; }
  const std::vector<SeamEdge>& seam_edges() const { return seam_edges_; }
  const std::vector<SeamCopyPair>& copy_pairs() const { return copy_pairs_; }
  // Values per original vertex → per cut vertex (every copy gets the original's value).
  std::vector<double> ToCut(const std::vector<double>& original) const;
  // Values per cut vertex → per original vertex (the value of the vertex's first copy).
  std::vector<double> ToOriginal(const std::vector<double>& cut_values) const;

 private:
  std::unique_ptr<SurfaceModel> cut_;
  std::vector<std::vector<int>> paths_;
  std::vector<char> starts_inside_;
  std::vector<int> original_vertex_;
  std::vector<int> first_copy_;
  std::vector<int> seam_of_cut_edge_;
  std::vector<SeamEdge> seam_edges_;
  std::vector<SeamCopyPair> copy_pairs_;
};

}  // namespace pqlayout
