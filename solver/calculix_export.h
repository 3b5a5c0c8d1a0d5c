// The frame model of solver/frame_analysis.h as a CalculiX (ccx 2.20) input deck, for
// cross-checking SolveFrame with an independent solver, and a reader for the displacements
// ccx prints to its .dat file. Pure functions: no files, no processes.
//
// Two element choices, because ccx 2.20 has no element that takes the section of a hollow
// tube *and* is an Euler–Bernoulli beam:
// - kU1 (default): ccx's two-node beam (user element U1, Luo's Timoshenko beam with
//   `*BEAM SECTION, SECTION=GENERAL`: A, I11, I12, I22, k). With the shear factor k huge
//   (1e9) its stiffness is the Euler–Bernoulli one. But in ccx 2.20 U1's bending along its
//   local 3-direction is wrong (measured: a right-angled two-member frame gives compliance
//   0.04–5.2× the beam answer, even negative, whenever that plane bends; bending along the
//   1-direction is right). So each member is written as two parallel U1 elements on the same
//   nodes, each with I22 = 0 and half the area: one with its 1-direction along the member's
//   local z and I11 = I_y, the twin with its 1-direction along local y and I11 = I_z. Their
//   sum is the model's 12-DOF stiffness exactly, except torsion: U1 twists with
//   G (I11 + I22), so the pair has G (I_y + I_z) — equal to the model's G J for a circular
//   hollow section, larger than Bredt's J for a rectangular one (the deck says so in a
//   comment). ccx then agrees with SolveFrame to the precision of its printout.
// - kB32R: three-node beams expanded by ccx into 20-node bricks with the section's true
//   shape (`SECTION=PIPE` or `BOX`; B31 refuses both: "*ERROR in gen3delem: first
//   thickness"). A 3D-continuum check of the beam theory, not of the same stiffness: ccx's
//   answer converges to the Euler–Bernoulli one only as members are subdivided.
// Each member becomes `subdivisions` elements in its own element set M<member + 1> (U1 twins:
// N<member + 1>), whose section line carries the member's orientation (M: the model's local
// z, the surface normal for a grid shell; for BOX the section's height lies along it). Nodes 1..n are the model's nodes
// (id = index + 1) with the same loads (*CLOAD) and restraints (*BOUNDARY); subdivision
// nodes follow.
#pragma once

#include <map>
#include <string>

#include "base/status.h"
#include "solver/frame_analysis.h"

namespace pqlayout {

enum class CalculixElement { kU1, kB32R };

// The section's shape, needed by kB32R (ccx meshes the tube itself); kU1 uses the model's
// section constants only.
struct CalculixSectionShape {
  enum Kind { kCircularHollow, kRectangularHollow } kind = kCircularHollow;
  double diameter = 0.0;   // circular: outside diameter D
  double width = 0.0;      // rectangular: along local y (in the surface)
  double height = 0.0;     // rectangular: along local z (the member's `up`)
  double thickness = 0.0;  // wall
};

struct CalculixExportOptions {
  CalculixElement element = CalculixElement::kU1;
  int subdivisions = 1;  // elements per member, ≥ 1
  CalculixSectionShape shape;
  std::string title = "pqlayout frame model";
  // > 0: the deck's step is *BUCKLE for this many load factors of the same *CLOAD (issue 18's
  // cross-check of solver/frame_buckling.h) instead of *STATIC. B32R only: ccx 2.20 has no
  // stress stiffness for U1 (it prints no factors).
  int buckling_modes = 0;
};

// Writes the deck: nodes, elements, material, sections, *BOUNDARY, one *STATIC step with
// *CLOAD and *NODE PRINT of U for the model's nodes (set NMODEL). InvalidInput if the model
// fails SolveFrame's checks, subdivisions < 1, or kB32R lacks a valid shape.
Status WriteCalculixDeck(const FrameModel& model, const CalculixExportOptions& options, std::string* deck);

// "u1" | "b32r" ↔ CalculixElement (config values).
const char* CalculixElementName(CalculixElement element);
bool CalculixElementFromName(const std::string& name, CalculixElement* element);

// The node displacements of the last "displacements" block of a ccx .dat file: node id →
// (u_x, u_y, u_z) (U1 nodes print rotations too; they are dropped). InvalidInput if there
// is no such block or a line does not parse.
Status ReadCalculixDisplacements(const std::string& dat_text, std::map<int, Eigen::Vector3d>* displacements);

// The factors of the "B U C K L I N G   F A C T O R   O U T P U T" block of a ccx .dat file,
// in mode order. InvalidInput if there is no such block or it holds no factor.
Status ReadCalculixBucklingFactors(const std::string& dat_text, std::vector<double>* factors);

}  // namespace pqlayout
