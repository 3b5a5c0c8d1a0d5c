#include "problems/edge_bracing_choice.h"

#include <algorithm>
#include <string>

#include <glog/logging.h>

#include "base/interrupt.h"
#include "geometry/edge_bracing.h"

namespace pqlayout {

std::vector<bool> FreeBoundaryVertices(const ExtractedMesh& mesh, const std::vector<Restraints>& restraints) {
  std::vector<bool> free(restraints.size());
  for (size_t v = 0; v < free.size(); ++v)
    free[v] = mesh.origin[v].on_boundary && std::none_of(restraints[v].begin(), restraints[v].end(), [](bool r) { return r; });
  return free;
}

Status BraceWherePays(const std::vector<bool>& free, const BracingEvaluator& evaluate, ExtractedMesh* mesh,
                      BracingChoice* choice) {
  *choice = BracingChoice();
  std::vector<std::vector<int>> stretches = FreeEdgeQuads(free, mesh->mesh);
  choice->stretches = static_cast<int>(stretches.size());
  const bool at_once = stretches.size() > static_cast<size_t>(kMaxBracingTrials);
  if (at_once) {
    std::vector<int> all;
    for (const auto& s : stretches) all.insert(all.end(), s.begin(), s.end());
    stretches = {all};
  }
  const ExtractedMesh unbraced = *mesh;
  PQ_RETURN_IF_ERROR(evaluate(mesh, &choice->compliance_unbraced));
  choice->compliance = choice->compliance_unbraced;
  choice->trials = 1;
  std::vector<int> kept;  // faces of the unbraced mesh cut so far
  int kept_quads = 0;
  for (size_t i = 0; i < stretches.size(); ++i) {
    const std::vector<int>& stretch = stretches[i];
    LOG(INFO) << "bracing: trying free stretch " << i + 1 << " of " << stretches.size()
              << (at_once ? " (all of them at once)" : "") << ", " << stretch.size() << " quads cut into triangles ...";
    std::vector<int> faces = kept;
    faces.insert(faces.end(), stretch.begin(), stretch.end());
    ExtractedMesh trial = unbraced;
    const int cut = CutQuads(faces, &trial);
    double c = 0.0;
    const bool ok = evaluate(&trial, &c).ok();
    if (!ok) PQ_RETURN_IF_ERROR(CheckInterrupt());  // a stop request is not "does not pay"
    ++choice->trials;
    choice->ratio.push_back(ok ? c / choice->compliance : 0.0);
    const bool pays = ok && c <= (1.0 - kBracingGain) * choice->compliance;
    LOG(INFO) << "bracing: free stretch " << i + 1 << ": "
              << (ok ? "compliance × " + std::to_string(c / choice->compliance) : std::string("the evaluation failed"))
              << (pays ? ", kept" : ", refused");
    if (pays) {
      kept = faces;
      kept_quads = cut;
      *mesh = std::move(trial);
      choice->compliance = c;
      choice->kept_trial = choice->trials - 1;
      choice->braced_stretches = at_once ? choice->stretches : choice->braced_stretches + 1;
    }
  }
  choice->braced_quads = kept_quads;
  return Status::Ok();
}

}  // namespace pqlayout
