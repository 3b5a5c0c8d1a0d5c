#include "geometry/level_lines.h"

#include <cmath>
#include <set>
#include <unordered_map>
#include <utility>

namespace pqlayout {
namespace {

using Polyline = std::vector<Eigen::Vector3d>;

// The crossing points of one level (graph nodes) and the oriented face segments between
// them (graph arcs). A node is a vertex exactly at the level (key = vertex index) or a point
// inside an edge (key = #V + edge index), so faces sharing a crossing share its node.
class LevelGraph {
 public:
  LevelGraph(const SurfaceModel& surface, const std::vector<double>& values, double value)
      : surface_(surface), values_(values), value_(value) {}

  bool Below(int v) const { return values_[v] < value_; }

  // The node where halfedge h (one end below the level, the other not) crosses it.
  int Crossing(HalfedgeHandle h) {
    const TriMesh& mesh = surface_.mesh();
    int lower = mesh.from_vertex_handle(h).idx(), upper = mesh.to_vertex_handle(h).idx();
    if (!Below(lower)) std::swap(lower, upper);
    const bool at_vertex = values_[upper] == value_;
    const int key = at_vertex ? upper : surface_.num_vertices() + mesh.edge_handle(h).idx();
    const auto [it, inserted] = node_of_key_.emplace(key, static_cast<int>(points_.size()));
    if (inserted) {
      const Eigen::Vector3d a = surface_.position(lower), b = surface_.position(upper);
      const double t = (value_ - values_[lower]) / (values_[upper] - values_[lower]);
      points_.push_back(at_vertex ? b : Eigen::Vector3d(a + t * (b - a)));
      is_vertex_.push_back(at_vertex);
    }
    return it->second;
  }

  // The segment of face f, oriented along n × ∇u: from the crossing where the face's
  // boundary walk goes from below to above, to the one where it goes back below.
  void AddFace(int f) {
    const TriMesh& mesh = surface_.mesh();
    int below = 0;
    for (const int v : surface_.face_vertices(f)) {
      if (!std::isfinite(values_[v])) return;
      below += Below(v);
    }
    if (below == 0 || below == 3) return;
    int from = -1, to = -1;
    HalfedgeHandle h = mesh.halfedge_handle(FaceHandle(f));
    for (int k = 0; k < 3; ++k, h = mesh.next_halfedge_handle(h)) {  // in face orientation
      const bool from_below = Below(mesh.from_vertex_handle(h).idx());
      const bool to_below = Below(mesh.to_vertex_handle(h).idx());
      if (from_below && !to_below) from = Crossing(h);
      if (!from_below && to_below) to = Crossing(h);
    }
    if (from == to) return;  // touches the level at one vertex only
    // Along an edge whose ends are both at the level: keep it once (a ridge at c).
    if (is_vertex_[from] && is_vertex_[to] &&
        !vertex_segments_.emplace(std::min(from, to), std::max(from, to)).second)
      return;
    arcs_.push_back({from, to});
  }

  // Chains the arcs into maximal polylines through nodes with one arc in and one out.
  std::vector<Polyline> Chain() const {
    const int n = static_cast<int>(points_.size());
    std::vector<int> in(n, 0), out(n, 0), next_arc(n, -1);
    for (size_t a = 0; a < arcs_.size(); ++a) {
      ++out[arcs_[a].first];
      ++in[arcs_[a].second];
      next_arc[arcs_[a].first] = static_cast<int>(a);
    }
    const auto pass_through = [&](int node) { return in[node] == 1 && out[node] == 1; };
    std::vector<char> used(arcs_.size(), 0);
    std::vector<Polyline> lines;
    const auto walk = [&](int arc) {
      Polyline line{points_[arcs_[arc].first]};
      while (true) {
        used[arc] = 1;
        const int node = arcs_[arc].second;
        line.push_back(points_[node]);
        if (!pass_through(node) || used[next_arc[node]]) break;
        arc = next_arc[node];
      }
      lines.push_back(std::move(line));
    };
    // Open lines (and pieces between saddle vertices) first, then the closed loops, which
    // end where they started: the walk stops on re-entering the used first arc.
    for (size_t a = 0; a < arcs_.size(); ++a)
      if (!used[a] && !pass_through(arcs_[a].first)) walk(static_cast<int>(a));
    for (size_t a = 0; a < arcs_.size(); ++a)
      if (!used[a]) walk(static_cast<int>(a));
    return lines;
  }

 private:
  const SurfaceModel& surface_;
  const std::vector<double>& values_;
  const double value_;
  std::unordered_map<int, int> node_of_key_;
  std::vector<Eigen::Vector3d> points_;           // per node
  std::vector<char> is_vertex_;                   // per node: a mesh vertex at the level
  std::set<std::pair<int, int>> vertex_segments_;  // node pairs of segments along an edge
  std::vector<std::pair<int, int>> arcs_;          // oriented segments, node to node
};

}  // namespace

std::vector<std::vector<Eigen::Vector3d>> LevelLines(const SurfaceModel& surface,
                                                     const std::vector<double>& values,
                                                     double value) {
  if (static_cast<int>(values.size()) != surface.num_vertices() || !std::isfinite(value))
    return {};
  LevelGraph graph(surface, values, value);
  for (int f = 0; f < surface.num_faces(); ++f) graph.AddFace(f);
  return graph.Chain();
}

}  // namespace pqlayout
