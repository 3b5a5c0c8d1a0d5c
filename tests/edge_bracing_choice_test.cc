// The choice of which free stretches to brace (problems/edge_bracing_choice.h), with an
// evaluator whose compliance is known: greedy, kept only at a gain of kBracingGain or more,
// a failing trial refused, the kept trial handed on as the evaluator left it.
#include <gtest/gtest.h>

#include <csignal>
#include <vector>

#include "base/interrupt.h"
#include "problems/edge_bracing_choice.h"
#include "tests/extraction_test_helpers.h"

namespace pqlayout {
namespace {

// 3 × 3 unit squares; the right column (vertices 3, 7, 11) and the top row (12, 13, 14) free,
// the corner 15 supported: two stretches, the right column's quads {2, 5} first.
ExtractedMesh Grid(std::vector<bool>* free) {
  ExtractedMesh out = extraction_test::QuadGrid3(0.0);
  free->assign(16, false);
  for (const int f : {3, 7, 11, 12, 13, 14}) (*free)[f] = true;
  return out;
}

bool InATriangle(const PolyMesh& mesh, int vertex) {
  for (const auto f : mesh.vf_range(VertexHandle(vertex)))
    if (mesh.valence(f) == 3) return true;
  return false;
}

// C = 100 − gain_right [right column cut] − gain_top [top row cut]; the evaluator lifts the
// mesh by 1 (as stiffen moves it) and fails when `fail_top` and the top row is cut.
BracingEvaluator Evaluator(double gain_right, double gain_top, bool fail_top, int* calls) {
  return [=](ExtractedMesh* mesh, double* c) {
    ++*calls;
    for (const auto v : mesh->mesh.vertices()) mesh->mesh.point(v)[2] += 1.0;
    const bool right = InATriangle(mesh->mesh, 7), top = InATriangle(mesh->mesh, 13);
    if (fail_top && top) return Status::Internal("singular");
    *c = 100.0 - (right ? gain_right : 0.0) - (top ? gain_top : 0.0);
    return Status::Ok();
  };
}

TEST(BracingChoice, KeepsTheStretchesThatPayOneAtATime) {
  std::vector<bool> free;
  ExtractedMesh mesh = Grid(&free);
  int calls = 0;
  BracingChoice choice;
  ASSERT_TRUE(BraceWherePays(free, Evaluator(20.0, 0.5, false, &calls), &mesh, &choice).ok());
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(choice.stretches, 2);
  EXPECT_EQ(choice.braced_stretches, 1);  // the right column (−20 %), not the top row (−0.6 %)
  EXPECT_EQ(choice.braced_quads, 2);
  EXPECT_EQ(choice.kept_trial, 1);
  EXPECT_DOUBLE_EQ(choice.compliance_unbraced, 100.0);
  EXPECT_DOUBLE_EQ(choice.compliance, 80.0);
  ASSERT_EQ(choice.ratio.size(), 2u);
  EXPECT_DOUBLE_EQ(choice.ratio[0], 0.8);
  EXPECT_DOUBLE_EQ(choice.ratio[1], 79.5 / 80.0);  // the top row tried on top of the right column
  EXPECT_TRUE(InATriangle(mesh.mesh, 7));
  EXPECT_FALSE(InATriangle(mesh.mesh, 13));
  EXPECT_DOUBLE_EQ(mesh.mesh.point(VertexHandle(0))[2], 1.0);  // as the evaluator left the kept trial
}

TEST(BracingChoice, AFailingTrialIsRefusedAndAFailingStartReturned) {
  std::vector<bool> free;
  ExtractedMesh mesh = Grid(&free);
  int calls = 0;
  BracingChoice choice;
  ASSERT_TRUE(BraceWherePays(free, Evaluator(20.0, 30.0, true, &calls), &mesh, &choice).ok());
  EXPECT_EQ(choice.braced_stretches, 1);
  EXPECT_DOUBLE_EQ(choice.ratio[1], 0.0);
  EXPECT_FALSE(InATriangle(mesh.mesh, 13));

  ExtractedMesh unbraced = Grid(&free);  // nothing pays: the start, evaluated, comes back
  ASSERT_TRUE(BraceWherePays(free, Evaluator(0.5, 0.0, false, &calls), &unbraced, &choice).ok());
  EXPECT_EQ(choice.braced_stretches, 0);
  EXPECT_EQ(choice.kept_trial, 0);
  EXPECT_EQ(unbraced.mesh.n_faces(), 9u);
  EXPECT_DOUBLE_EQ(unbraced.mesh.point(VertexHandle(0))[2], 1.0);

  const BracingEvaluator broken = [](ExtractedMesh*, double*) { return Status::Internal("singular"); };
  EXPECT_FALSE(BraceWherePays(free, broken, &unbraced, &choice).ok());
}

TEST(BracingChoice, NoFreeEdgeMeansOneEvaluation) {
  std::vector<bool> free;
  ExtractedMesh mesh = Grid(&free);
  int calls = 0;
  BracingChoice choice;
  ASSERT_TRUE(BraceWherePays(std::vector<bool>(16, false), Evaluator(20.0, 20.0, false, &calls), &mesh, &choice).ok());
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(choice.stretches, 0);
  EXPECT_EQ(mesh.mesh.n_faces(), 9u);
}

// A trial that fails because the run was interrupted stops the choice with the interrupt.
TEST(BracingChoice, AnInterruptedTrialStopsTheChoice) {
  std::vector<bool> free;
  ExtractedMesh mesh = Grid(&free);
  int calls = 0;
  const BracingEvaluator base = Evaluator(20.0, 20.0, false, &calls);
  const BracingEvaluator interrupted = [&](ExtractedMesh* m, double* c) {
    if (calls == 1) {  // the first trial after the unbraced evaluation
      SetInterruptForTesting(SIGINT);
      ++calls;
      return Status::Internal("interrupted");
    }
    return base(m, c);
  };
  BracingChoice choice;
  const Status status = BraceWherePays(free, interrupted, &mesh, &choice);
  SetInterruptForTesting(0);
  ClearInterrupt();
  EXPECT_FALSE(status.ok());
  EXPECT_EQ(calls, 2);  // the second stretch was not tried
}

}  // namespace
}  // namespace pqlayout
