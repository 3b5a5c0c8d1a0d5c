// The problems' options: one struct per stage, every field with its default and a one-line
// comment. Config keys are the dotted snake_case paths of these fields
// (`levelset.weights.alignment`); pipeline/config.h gathers the structs into Config, and the
// key table in pipeline/config.cc binds each key to its field, type, range and comment, and is
// the single source for parsing, `--set`, the resolved config in report.json and the config
// reference (`pqlayout keys`). A problem takes its own struct, never the whole Config.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "base/status.h"

namespace pqlayout {

// How a boundary vertex is supported (SPEC §2 and §7).
enum class BoundaryCondition { kFixed, kFree, kClamped, kSliding };
const char* BoundaryConditionName(BoundaryCondition c);

// Which boundary vertices a rule applies to.
struct BoundarySelector {
  enum class Kind { kAll, kLoop, kOuter, kInner, kBox, kIds, kIdsFile, kCorners };
  Kind kind = Kind::kAll;
  int loop = -1;                                        // kLoop: index, 0 = outer loop
  Eigen::Vector3d box_min = Eigen::Vector3d::Zero();    // kBox: axis-aligned box, metres
  Eigen::Vector3d box_max = Eigen::Vector3d::Zero();
  std::vector<int> ids;                                 // kIds: vertex ids
  std::string ids_file;                                 // kIdsFile: file of vertex ids
};

struct BoundaryRule {
  BoundarySelector select;
  BoundaryCondition condition = BoundaryCondition::kFixed;
  std::string origin;  // where the rule was written ("file.yaml:12" or "--set boundary.rules"), for messages
};

struct SurfaceOptions {
  std::string file;                   // reference mesh (OBJ/PLY/OFF/STL, metres); relative to the config file
  std::string generator = "great_court";  // built-in surface when no file is given
  double edge_length = 1.5;           // generator: target triangle edge length, m
  double width = 30.0;                // generator: x extent, m (disk/annulus: outer diameter)
  double depth = 30.0;                // generator: y extent, m (annulus: inner diameter)
  double rise = 5.0;                  // generator: crown height above the supports, m
  double weld_tolerance = 0.0;        // file: seam vertices this close are one, m; 0: 1e-6 × the diagonal
};

struct BoundaryOptions {
  BoundaryCondition default_condition = BoundaryCondition::kFixed;  // key: boundary.default
  std::vector<BoundaryRule> rules;    // applied in order, later rules win
};

struct LoadOptions {
  double q = 1350.0;  // dead load per area for the membrane solve, N/m² (glazed steel grid shell)
};

struct MembraneOptions {
  double stiffness = 1.0e6;  // λ_m, membrane stiffness, N/m (scales v; ε's directions only weakly)
  double bending = 0.0;      // λ_b, bending stiffness, N·m (0 = the paper's pure membrane)
};

struct GuidanceOptions {
  std::string source = "strain";  // strain | curvature | file
  double threshold = 0.2;  // no alignment where |ε_max| < threshold × max |ε_max|
  double ramp = 0.1;       // weight ramps 0 → 1 over [threshold, threshold + ramp] × max
  std::string file;        // source = file: per-face CSV (id,dx,dy,dz[,weight])
  // Where the source's weight is below 1 (strain: where the membrane barely strains, which the
  // paper leaves to "don't care"), the principal curvature lines fill in: curvature | none
  // (problems/guidance.h, AddCurvatureFallback). Not for source = curvature.
  std::string fallback = "curvature";
  double fallback_weight = 0.5;  // β: the fallback's weight is (1 − w_source) · β · w_curvature
  // Strain weights where the principal strains have opposite signs: weak (from |ε_max| − |ε_min|,
  // zero where the largest-modulus rule swaps e_max by 90°) | paper (from |ε_max| everywhere).
  std::string shear_switch = "weak";
};

struct LayoutOptions {
  double spacing = 3.0;  // h: distance between neighbouring level lines, m
  // spacing: the level lines are solved to lie h apart; panel_area: afterwards φ and ψ are
  // scaled by one common factor so that the mean panel (cell) area is h² — layouts whose
  // families cross at different angles then get the same number of nodes per area; auto:
  // spacing for `run` and `sweep`, panel_area for `compare` (a structural comparison is only
  // fair at equal node counts, as in the paper).
  std::string density = "auto";
  // Refuse a spacing that would give more panels than this, estimated as area / h² before
  // anything is solved: the level-set solve's and the extraction's time and memory grow with it.
  int max_panels = 100000;
};

// Defaults from a weight sweep on the Great Court (README, "Level sets"): the terms are
// area integrals of dimensionless quantities, so the weights carry over to other roofs.
struct LevelsetWeights {
  double alignment = 10.0;        // φ's level lines follow the guidance
  double spacing = 5.0;           // h|∇φ| = 1 and h|∇ψ| = 1
  double smoothness = 0.01;       // h² × gradient jump per unit length across interior edges
  double conjugacy = 1.0;         // II(n×∇φ, n×∇ψ) = 0
  double transversality = 100.0;  // crossing angle ≥ levelset.min_angle, no fold-overs
};

struct LevelsetOptions {
  LevelsetWeights weights;
  double min_angle = 30.0;  // minimum crossing angle of the two families, degrees
  // The smoothness term acts on interior edges with a face whose guidance weight is ≤ this
  // (1: every edge, the default; 0.5: only where the guidance leaves φ's direction open, level
  // sets ~1.3–1.6× faster, but the Great Court's curvature layout then crosses at 29.4°;
  // benchmarks/RESULTS.md, "Where the level sets' time goes").
  double smoothness_max_guidance = 1.0;
  // How each Levenberg–Marquardt step's normal equations are solved: "cholesky" (Eigen's sparse
  // factor, exact) or "cg" (conjugate gradients preconditioned by the factor without the
  // smoothness terms, which are most of its fill: the joint solve's steps ~2× cheaper, level
  // sets ~1.2–1.6× faster, a different layout; benchmarks/RESULTS.md, "The level sets' steps by
  // conjugate gradients").
  std::string linear_solver = "cholesky";
  // A layout with branch points (tips of sign −1 seams) that still crosses below min_angle or
  // folds over after its rounds is solved again with the spacing asked for within this × h of
  // each branch point following the cone it makes, h|∇u| = (d / (tip_cone_radius · h))^½ at
  // distance d instead of 1, and the better end kept (0: no second solve). Level lines cannot be
  // h apart there without shearing the cells, and the shear is where the worst crossing was a
  // draw (benchmarks/RESULTS.md, "The cone's spacing round the branch points").
  double tip_cone_radius = 1.5;
  // Whether the second layouts that may be needed — that second solve, and the layout with
  // poles (levelset.poles) — are started on threads of their own as the first layout's begins:
  // "true", "false" (one thread, each only once it is needed), "auto" (as many at once as the
  // machine has hardware threads less one: AlongsideBudget) or "1" (one at a time: auto's
  // schedule on 2 cores, on any machine). One that turns out not to be needed
  // is cancelled as soon as that is known. Each solve is single-threaded on its own data, so the
  // outputs are the same either way (benchmarks/RESULTS.md, "The second layouts alongside the
  // first, cancelled when not needed").
  std::string alongside = "auto";
  // Whether φ is solved alone and then ψ with φ held before the joint solve (the paper's order),
  // or the joint solve starts from the initial guess (the default since 2026-12-06: over the
  // Great Court's seven meshes 0.93× (strain) and 0.97× (curvature) the compliance after
  // stiffen, the corpus as stiff, its level sets 3× faster: benchmarks/RESULTS.md, "The joint
  // solve from the initial guess").
  bool separate_solves = false;
  int max_iterations = 50;    // Ceres iterations of the φ solve and of the ψ solve (separate_solves only)
  int joint_iterations = 300; // Ceres iterations of the joint solve, at most (0: none, separate_solves only; stall stop past 100)
  int crossing_rounds = 10;   // local re-solves raising transversality where the crossing is below min_angle, at most (0: none); floor rounds too where they fail
  bool seams = true;          // cut branch seams at guidance singularities and holes (φ, ψ jump across them)
  bool poles = true;          // a crown of the guidance (index +1) becomes a pole with a cap (needs seams)
  double working_edge = 0.0;  // edge length of the mesh φ, ψ are solved on, m (0: 0.4 h, 0.8 h if draft, or working_triangles' edge); a finer reference is remeshed
  bool draft = false;         // a quick look: the working mesh's edge 0.8 h (≤ 1/16 of the shortest boundary loop) instead of 0.4 h
  int working_triangles = 12000;  // working edge ≥ that of this many equilateral triangles over the roof, ≤ 1.5 h (0: 0.4 h)
};

struct ExtractOptions {
  double corner_angle = 30.0;  // boundary turning angle above which a vertex is a corner, degrees
  double min_edge = 0.2;       // edges shorter than min_edge × h are merged
  double boundary_tolerance = 0.01;  // boundary edges further than this × h from the reference boundary are split
  std::string brace_free_edges = "paying";  // none | paying (stretches whose bracing lowers C after stiffen ≥ 1 %) | all
};

struct PlanarizeWeights {
  double planarity = 1.0;   // faces planar
  double closeness = 1.0;   // vertices on the reference surface
  double boundary = 1.0;    // boundary vertices on the reference boundary
  double fairness = 0.01;   // second differences along the mesh polylines
  double anchor = 1.0;      // vertices stay near where the layout put them (raised with closeness, ×3 a round)
  double edge_length = 0.0; // × planarity weight: no edge below ¼ of its extracted length (of h); 0: off
  double orientation = 1.0; // × the first round's planarity weight: no triangle turns over or flattens (< 5 % of its area); 0: off
};

struct PlanarizeOptions {
  PlanarizeWeights weights;
  double target_delta = 1e-3;  // stop when max planarity δ ≤ target
  int max_rounds = 20;         // outer rounds (closest-point refresh, planarity weight raise)
  double close_edges = 0.1;    // × h: edges planarisation shortens below this are closed, then planarised again (0: never)
  double split_warped = 0.05;  // quads with δ above this as extracted are cut into two triangles first (0: none)
};

struct StiffenWeights {
  double fairness = 0.1;     // polylines keep the second differences of the planarised mesh (kinks)
  double edge_length = 1.0;  // members stay longer than max(1.1 × section depth, min_member × planarised length)
};

// Stage stiffen (problems/stiffen.h): the planarised shell reshaped within `tolerance` of the
// reference so that the frame's compliance drops, faces kept planar.
struct StiffenOptions {
  // How far (m) a vertex may be from the reference surface, both sides; 0: stage off.
  // 0.1 m: a change an architect reads as the same roof (a third of a percent of the Great
  // Court's span), and it takes 26 % (strain grid) to 40 % (curvature grid) off the Great
  // Court's compliance (README, "Stiffen").
  double tolerance = 0.1;
  double slide = 0.1;         // how far (m) a vertex may also move along the reference (each tangent direction; at most 0.1 h)
  double min_member = 0.75;   // no member shorter than this × its planarised length
  int max_iterations = 1000;   // L-BFGS iterations in all (each one or two frame solves)
  // The stage ends once stop_window iterations lowered its objective by less than stop_gain of
  // it (20 and 0.5 %: C/C₀ within ~0.5 % of its converged value on the Great Court; --draft
  // asks 5 and 1 %: ~1 % softer, the stage ~4× faster; benchmarks/RESULTS.md).
  int stop_window = 20;
  double stop_gain = 0.005;
  StiffenWeights weights;
};

struct MaterialOptions {
  double youngs_modulus = 210e9;  // E, Pa (steel)
  double poisson_ratio = 0.3;     // ν; G = E / (2(1+ν))
  double density = 7850.0;        // ρ, kg/m³
  double yield_strength = 355e6;  // f_y, Pa (S355): member utilisation (solver/member_checks.h)
};

struct SectionOptions {
  std::string shape = "circular_hollow";  // circular_hollow | rectangular_hollow
  double diameter = 0.1143;   // circular hollow: outside diameter D, m
  double thickness = 0.005;   // wall thickness t, m
  double width = 0.06;        // rectangular hollow: width (in the surface), m
  double height = 0.12;       // rectangular hollow: height (along the surface normal), m
};

// What a run writes besides the layout, the analysis, the figures and the report.
struct OutputOptions {
  // fields/vertices.csv, fields/faces.csv, fields/levelsets.csv and fields.vtk: per element
  // of the reference, so ~300 MB at a million triangles; sweeps may not want them.
  bool fields = true;
};

struct AnalysisOptions {
  double panel_load = 1000.0;  // panel dead load, N/m² of face area
  double gravity = 9.81;       // g, m/s²
  bool export_calculix = false;  // also write analysis/model.inp for CalculiX
  std::string calculix_element = "u1";  // u1 (same Euler–Bernoulli stiffness) | b32r (expanded to bricks)
  int calculix_subdivisions = 1;        // CalculiX elements per member
  int buckling_modes = 3;               // linear buckling factors to find (0: no buckling analysis)
  MaterialOptions material;
  SectionOptions section;
};

}  // namespace pqlayout
