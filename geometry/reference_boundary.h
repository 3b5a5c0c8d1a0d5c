// The reference surface's boundary as arc-length parametrised polylines: closest points,
// points at an arc length, a chord's deviation from the part of the boundary it spans, and
// the kinks (vertices where the boundary turns) that boundary refinement puts vertices on.
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Core>

#include "geometry/quad_extraction.h"
#include "geometry/surface_model.h"

namespace pqlayout {

// The reference surface's boundary loops as polylines parametrised by arc length.
class ReferenceBoundary {
 public:
  explicit ReferenceBoundary(const SurfaceModel& surface);

  struct Location {
    int loop = -1;          // index into SurfaceModel::boundary_loops()
    double arc = 0.0;       // arc length from the loop's first vertex, metres
    double distance = 0.0;  // from the query point to the loop
  };
  // The closest point of any boundary loop, by brute force over the boundary edges: they are
  // few (~2,500 at 1M triangles) and the extraction makes a few thousand queries, whereas
  // ClosestPointQuery::OnBoundary would first build its triangle tree (~1 s at 1M).
  Location Locate(const Eigen::Vector3d& p) const;
  double Distance(const Eigen::Vector3d& p) const { return Locate(p).distance; }

  // The point at arc length `arc` (modulo the length) of loop `loop`: its position and its
  // reference triangle with barycentric coordinates (on_boundary set).
  QuadMeshVertex PointAt(int loop, double arc, Eigen::Vector3d* position) const;
  double length(int loop) const { return loops_[loop].arc.back(); }

  // Largest distance between the segment a–b and the part of `loop` from arc `from` forward
  // by `span` metres (both ways: points of the segment to the loop, the loop's vertices in
  // the span to the segment).
  double ChordDeviation(const Eigen::Vector3d& a, const Eigen::Vector3d& b, int loop, double from,
                        double span) const;
  // Of the loop vertices more than `margin` inside the same span where the boundary turns by
  // more than `min_turn` radians (kinks), the one farthest from the segment a–b: its arc length
  // from `from`, or -1 if the span holds none. A kink within `margin` of an end counts as that
  // end (a vertex put there would make an edge shorter than `margin`).
  double FarthestKink(const Eigen::Vector3d& a, const Eigen::Vector3d& b, int loop, double from, double span,
                      double min_turn, double margin) const;
  // The angle (radians) by which the boundary turns at the loop vertex within `within` of p,
  // 0 if no loop vertex is that close.
  double TurnAt(const Eigen::Vector3d& p, double within) const;
  // The signed arc length from `arc` to the nearest vertex of `loop` within `reach` either way at
  // which the boundary turns by more than `min_turn` radians; NaN if there is none.
  double NearestKink(int loop, double arc, double reach, double min_turn) const;

 private:
  struct Loop {
    std::vector<int> vertices;  // reference vertex ids
    std::vector<double> arc;    // arc length at each vertex, and the total at the end (size n + 1)
    std::vector<double> turn;   // angle between the segments before and after each vertex, radians
  };
  Eigen::Vector3d Position(int loop, double arc, int* segment, double* t) const;
  // The loop's vertices strictly inside the span: (arc length from `from`, index in the loop).
  std::vector<std::pair<double, int>> VerticesInside(int loop, double from, double span) const;

  const SurfaceModel& surface_;
  std::vector<Loop> loops_;
};

// The turning angle above which a kink of the reference boundary is sharp: a chord that cuts it
// at min_edge from the kink stands more than `tolerance` off (min_edge · sin(θ/2) > tolerance;
// 5.7° at the defaults). Infinite if min_edge ≤ tolerance.
double SharpKinkTurn(double tolerance, double min_edge);

}  // namespace pqlayout
