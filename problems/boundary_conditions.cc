#include "problems/boundary_conditions.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace pqlayout {

const char* BoundaryConditionName(BoundaryCondition c) {
  switch (c) {
    case BoundaryCondition::kFixed: return "fixed";
    case BoundaryCondition::kFree: return "free";
    case BoundaryCondition::kClamped: return "clamped";
    case BoundaryCondition::kSliding: return "sliding";
  }
  return "?";
}

namespace {

// An id and where it was written: "" for the config (the rule's origin says where), or
// "ids.txt:3" for an ids_file.
struct VertexId {
  long long id;
  std::string where;
};

Status ReadIdsFile(const std::string& path, std::vector<VertexId>* ids) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return Status::InvalidInput(path + ": vertex-id file not found");
  if (!std::filesystem::is_regular_file(path, ec)) return Status::InvalidInput(path + ": not a vertex-id file (a folder?)");
  std::ifstream in(path);
  if (!in) return Status::InvalidInput(path + ": cannot read the vertex-id file");
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    for (char& ch : line)
      if (ch == ',' || ch == ';' || ch == '\t' || ch == '\r') ch = ' ';
    std::istringstream words(line);
    std::string word;
    const std::string where = path + ":" + std::to_string(line_number);
    while (words >> word) {
      size_t used = 0;
      long long id = -1;
      try {
        id = std::stoll(word, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != word.size() || id < 0)
        return Status::InvalidInput(where + ": '" + word + "' is not a vertex id (ids are whole numbers from 0)");
      ids->push_back({id, where});
    }
  }
  return Status::Ok();
}

// The boundary vertices an ids or ids_file selector picks; ids are the file's vertices when
// file_vertex is given (see ReadSurfaceMesh), else the surface's.
Status SelectIds(const BoundarySelector& s, const SurfaceModel& surface, const std::vector<int>* file_vertex,
                 std::vector<int>* picked) {
  std::vector<VertexId> ids;
  for (const int v : s.ids) ids.push_back({v, ""});
  if (s.kind == BoundarySelector::Kind::kIdsFile) PQ_RETURN_IF_ERROR(ReadIdsFile(s.ids_file, &ids));
  const int count = file_vertex ? static_cast<int>(file_vertex->size()) : surface.num_vertices();
  for (const auto& [id, where] : ids) {
    auto refuse = [&where = where, id = id](const std::string& what) {
      return Status::InvalidInput((where.empty() ? "" : where + ": ") + "vertex " + std::to_string(id) + what);
    };
    // Negative ids are refused when read; checked again here because they index arrays.
    if (id < 0 || id >= count)
      return refuse(" does not exist (the " + std::string(file_vertex ? "file" : "surface") + " has " +
                    std::to_string(count) + " vertices, numbered from 0)");
    const int v = file_vertex ? (*file_vertex)[id] : static_cast<int>(id);
    if (v < 0) return refuse(" is used by no triangle of the file");
    if (!surface.is_boundary(v)) return refuse(" is not a boundary vertex");
    picked->push_back(v);
  }
  return Status::Ok();
}

// The boundary vertices a selector picks.
Status Select(const BoundarySelector& s, const SurfaceModel& surface, double corner_angle,
              const std::vector<int>* file_vertex, std::vector<int>* picked) {
  using K = BoundarySelector::Kind;
  const auto& loops = surface.boundary_loops();
  auto add_loop = [&](size_t l) {
    for (const auto v : loops[l].vertices) picked->push_back(v.idx());
  };
  switch (s.kind) {
    case K::kAll:
      for (size_t l = 0; l < loops.size(); ++l) add_loop(l);
      return Status::Ok();
    case K::kOuter: add_loop(0); return Status::Ok();
    case K::kInner:
      if (loops.size() < 2) return Status::InvalidInput("selects inner loops but the surface has only one boundary loop");
      for (size_t l = 1; l < loops.size(); ++l) add_loop(l);
      return Status::Ok();
    case K::kLoop:
      if (s.loop >= static_cast<int>(loops.size()))
        return Status::InvalidInput("selects loop " + std::to_string(s.loop) + " but the surface has " +
                                    std::to_string(loops.size()) + " boundary loop(s), numbered from 0 (outer)");
      add_loop(s.loop);
      return Status::Ok();
    case K::kCorners:
      *picked = surface.BoundaryCorners(corner_angle * M_PI / 180.0);
      return Status::Ok();
    case K::kBox:
      for (int v = 0; v < surface.num_vertices(); ++v) {
        const Eigen::Vector3d p = surface.position(v);
        if (surface.is_boundary(v) && (p.array() >= s.box_min.array()).all() && (p.array() <= s.box_max.array()).all())
          picked->push_back(v);
      }
      return Status::Ok();
    case K::kIds:
    case K::kIdsFile: return SelectIds(s, surface, file_vertex, picked);
  }
  return Status::Internal("unknown selector");
}

}  // namespace

Status ResolveBoundaryConditions(const BoundaryOptions& options, const SurfaceModel& surface,
                                 double corner_angle, VertexConditions* conditions,
                                 const std::vector<int>* file_vertex) {
  conditions->assign(surface.num_vertices(), std::nullopt);
  for (int v = 0; v < surface.num_vertices(); ++v)
    if (surface.is_boundary(v)) (*conditions)[v] = options.default_condition;
  for (size_t r = 0; r < options.rules.size(); ++r) {
    const BoundaryRule& rule = options.rules[r];
    const std::string name = (rule.origin.empty() ? "" : rule.origin + ": ") + "boundary.rules[" + std::to_string(r) + "]";
    std::vector<int> picked;
    const Status selected = Select(rule.select, surface, corner_angle, file_vertex, &picked);
    // A message that starts with an ids_file's name and line keeps them first.
    if (!selected.ok() && rule.select.kind == BoundarySelector::Kind::kIdsFile &&
        selected.message().rfind(rule.select.ids_file + ":", 0) == 0)
      return Status::InvalidInput(selected.message() + " (" + name + ")");
    PQ_RETURN_IF_ERROR(selected.WithContext(name));
    if (picked.empty()) return Status::InvalidInput(name + ": selects no boundary vertex");
    for (const int v : picked) (*conditions)[v] = rule.condition;
  }
  return Status::Ok();
}

Status CheckSupportsHoldTheFrameInPlan(const VertexConditions& conditions) {
  int fixed = 0, clamped = 0, sliding = 0;
  for (const auto& c : conditions) {
    if (!c) continue;
    fixed += *c == BoundaryCondition::kFixed;
    clamped += *c == BoundaryCondition::kClamped;
    sliding += *c == BoundaryCondition::kSliding;
  }
  // No support at all: the membrane stage names the part it cannot hold, more precisely.
  if (clamped > 0 || fixed >= 2 || fixed + sliding == 0) return Status::Ok();
  return Status::InvalidInput(
      "boundary: the supports cannot hold the frame in plan (" + std::to_string(fixed) + " fixed, 0 clamped, " +
      std::to_string(sliding) + " sliding boundary vertices: sliding holds u_z only), so it can " +
      (fixed == 1 ? "turn about the fixed vertex" : "slide and turn") +
      " in plan as a whole, a mechanism for stiffen and analyze; fix or clamp at least two boundary vertices "
      "(e.g. boundary.rules: [{select: corners, condition: fixed}]) or stop at --until planarize");
}

}  // namespace pqlayout
