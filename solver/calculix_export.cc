#include "solver/calculix_export.h"

#include <cstdio>
#include <sstream>
#include <vector>

namespace pqlayout {
namespace {

// ccx reads node coordinates and direction vectors from 20-character fields: %.12g never
// needs more (sign, 12 digits, point, exponent).
std::string Num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.12g", v);
  return buffer;
}

std::string Vec(const Eigen::Vector3d& v) { return Num(v.x()) + "," + Num(v.y()) + "," + Num(v.z()); }

// Shear factor of the U1 section: large enough that shear deformation (∝ 1/k) is below
// the .dat printout's 7 digits, small enough that Luo's stiffness terms (∝ k² L⁴) stay far
// from overflow and cancellation.
constexpr double kEulerBernoulliShearFactor = 1e9;

Status CheckInput(const FrameModel& m, const CalculixExportOptions& o) {
  const int n = static_cast<int>(m.nodes.size());
  if (n == 0 || m.members.empty()) return Status::InvalidInput("calculix export: no nodes or no members");
  if (o.subdivisions < 1) return Status::InvalidInput("calculix export: subdivisions must be at least 1");
  if (o.buckling_modes > 0 && o.element != CalculixElement::kB32R)
    return Status::InvalidInput("calculix export: a *BUCKLE step needs B32R elements (ccx has no U1 stress stiffness)");
  for (size_t e = 0; e < m.members.size(); ++e) {
    const FrameMember& mb = m.members[e];
    if (mb.a < 0 || mb.b < 0 || mb.a >= n || mb.b >= n || !((m.nodes[mb.a] - m.nodes[mb.b]).norm() > 0.0))
      return Status::InvalidInput("calculix export: member " + std::to_string(e) + " has invalid end nodes");
  }
  if (o.element == CalculixElement::kB32R) {
    const CalculixSectionShape& s = o.shape;
    const bool ok = s.kind == CalculixSectionShape::kCircularHollow
                        ? s.thickness > 0 && 2 * s.thickness < s.diameter
                        : s.thickness > 0 && 2 * s.thickness < s.width && 2 * s.thickness < s.height;
    if (!ok) return Status::InvalidInput("calculix export: B32R needs the section's shape (diameter/width/height, thickness)");
  }
  return Status::Ok();
}

// The *BEAM SECTION data line after the header, without the orientation line. U1 (see the
// header): half the area and one bending stiffness per twin, I22 = 0; twin = false is the
// element bending along local z (I_y), twin = true the one bending along local y (I_z).
std::string SectionLine(const FrameModel& m, const CalculixExportOptions& o, bool twin) {
  if (o.element == CalculixElement::kU1)  // A, I11 (bending along the 1-direction), I12, I22, k
    return Num(m.section.area / 2) + "," + Num(twin ? m.section.inertia_z : m.section.inertia_y) + ",0,0," +
           Num(kEulerBernoulliShearFactor);
  const CalculixSectionShape& s = o.shape;
  if (s.kind == CalculixSectionShape::kCircularHollow) return Num(s.diameter / 2) + "," + Num(s.thickness);
  const std::string t = Num(s.thickness);  // a along the 1-direction, b along the 2-direction, 4 walls
  return Num(s.height) + "," + Num(s.width) + "," + t + "," + t + "," + t + "," + t;
}

}  // namespace

const char* CalculixElementName(CalculixElement element) { return element == CalculixElement::kU1 ? "u1" : "b32r"; }

bool CalculixElementFromName(const std::string& name, CalculixElement* element) {
  if (name == "u1") *element = CalculixElement::kU1;
  else if (name == "b32r") *element = CalculixElement::kB32R;
  else return false;
  return true;
}

Status WriteCalculixDeck(const FrameModel& m, const CalculixExportOptions& o, std::string* deck) {
  PQ_RETURN_IF_ERROR(CheckInput(m, o));
  const bool u1 = o.element == CalculixElement::kU1;
  const int n = static_cast<int>(m.nodes.size());
  const int k = o.subdivisions, per_element = u1 ? 1 : 2;  // new nodes per element along a member
  const double E = m.material.youngs_modulus, G = m.material.shear_modulus;
  const double nu = E / (2.0 * G) - 1.0;
  std::ostringstream s;
  s << "** " << o.title << "\n** " << n << " frame nodes, " << m.members.size() << " members, "
    << k << " " << (u1 ? "U1" : "B32R") << " element(s) per member (pqlayout solver/calculix_export.h)\n"
    << "** Units: m, N, Pa. Run: ccx -i model   (displacements of the frame nodes in model.dat)\n";
  s << "*NODE, NSET=NMODEL\n";
  for (int i = 0; i < n; ++i) s << i + 1 << "," << Vec(m.nodes[i]) << "\n";
  // Subdivision nodes, member by member: ids n+1, n+2, ...
  std::vector<std::vector<int>> chain(m.members.size());
  int next_node = n + 1;
  std::ostringstream extra;
  for (size_t e = 0; e < m.members.size(); ++e) {
    const FrameMember& mb = m.members[e];
    const int steps = k * per_element;
    chain[e].push_back(mb.a + 1);
    for (int j = 1; j < steps; ++j) {
      extra << next_node << "," << Vec(m.nodes[mb.a] + (m.nodes[mb.b] - m.nodes[mb.a]) * (double(j) / steps)) << "\n";
      chain[e].push_back(next_node++);
    }
    chain[e].push_back(mb.b + 1);
  }
  if (next_node > n + 1) s << "*NODE, NSET=NSUB\n" << extra.str();
  if (u1) s << "*USER ELEMENT, TYPE=U1, INTEGRATION POINTS=2, MAXDOF=6, NODES=2\n";
  int next_element = 1;
  auto write_elements = [&](const std::string& elset, size_t e) {
    s << "*ELEMENT, TYPE=" << (u1 ? "U1" : "B32R") << ", ELSET=" << elset << "\n";
    for (int j = 0; j < k; ++j) {
      s << next_element++;
      for (int q = 0; q <= per_element; ++q) s << "," << chain[e][j * per_element + q];
      s << "\n";
    }
  };
  for (size_t e = 0; e < m.members.size(); ++e) {
    write_elements("M" + std::to_string(e + 1), e);
    if (u1) write_elements("N" + std::to_string(e + 1), e);  // the parallel twin, bending along local y
  }
  s << "*MATERIAL, NAME=FRAME\n*ELASTIC\n" << Num(E) << "," << Num(nu) << "\n";
  if (u1 && std::abs(m.section.torsion - m.section.inertia_y - m.section.inertia_z) > 1e-9 * m.section.torsion)
    s << "** U1 twists with G (I11 + I22) = G " << Num(m.section.inertia_y + m.section.inertia_z)
      << ", not the model's G J = G " << Num(m.section.torsion) << "\n";
  const char* kind = u1 ? "GENERAL" : o.shape.kind == CalculixSectionShape::kCircularHollow ? "PIPE" : "BOX";
  for (size_t e = 0; e < m.members.size(); ++e) {
    const FrameMember& mb = m.members[e];
    const Eigen::Matrix3d R = MemberFrame<double>(m.nodes[mb.a], m.nodes[mb.b], mb.up);
    s << "*BEAM SECTION, ELSET=M" << e + 1 << ", MATERIAL=FRAME, SECTION=" << kind << "\n"
      << SectionLine(m, o, false) << "\n" << Vec(R.row(2).transpose()) << "\n";  // 1-direction: the member's local z
    if (u1)
      s << "*BEAM SECTION, ELSET=N" << e + 1 << ", MATERIAL=FRAME, SECTION=" << kind << "\n"
        << SectionLine(m, o, true) << "\n" << Vec(R.row(1).transpose()) << "\n";  // 1-direction: local y
  }
  s << "*BOUNDARY\n";
  for (int i = 0; i < n && !m.restraints.empty(); ++i)
    for (int d = 0; d < 6;) {
      if (!m.restraints[i][d]) { ++d; continue; }
      int last = d;
      while (last + 1 < 6 && m.restraints[i][last + 1]) ++last;
      s << i + 1 << "," << d + 1 << "," << last + 1 << "\n";
      d = last + 1;
    }
  s << "*STEP\n";
  if (o.buckling_modes > 0)
    s << "*BUCKLE\n" << o.buckling_modes << "\n";
  else
    s << "*STATIC\n";
  s << "*CLOAD\n";
  for (int i = 0; i < n && !m.loads.empty(); ++i)
    for (int d = 0; d < 6; ++d)
      if (m.loads[i][d] != 0.0) s << i + 1 << "," << d + 1 << "," << Num(m.loads[i][d]) << "\n";
  if (o.buckling_modes == 0) s << "*NODE PRINT, NSET=NMODEL\nU\n";
  s << "*NODE FILE\nU\n*END STEP\n";
  *deck = s.str();
  return Status::Ok();
}

Status ReadCalculixDisplacements(const std::string& dat, std::map<int, Eigen::Vector3d>* u) {
  std::vector<std::string> lines;
  std::istringstream in(dat);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  size_t header = lines.size();
  for (size_t i = 0; i < lines.size(); ++i)
    if (lines[i].find("displacements") != std::string::npos) header = i;
  if (header == lines.size()) return Status::InvalidInput("ccx .dat: no displacements block");
  u->clear();
  for (size_t i = header + 1; i < lines.size(); ++i) {
    if (lines[i].find_first_not_of(" \t\r") == std::string::npos) {
      if (u->empty()) continue;  // the blank line after the header
      break;
    }
    std::istringstream row(lines[i]);
    int node = 0;
    Eigen::Vector3d v;
    if (!(row >> node >> v.x() >> v.y() >> v.z()))
      return Status::InvalidInput("ccx .dat line " + std::to_string(i + 1) + ": expected node u_x u_y u_z");
    (*u)[node] = v;
  }
  if (u->empty()) return Status::InvalidInput("ccx .dat: empty displacements block");
  return Status::Ok();
}

Status ReadCalculixBucklingFactors(const std::string& dat, std::vector<double>* factors) {
  std::istringstream in(dat);
  factors->clear();
  bool block = false;
  for (std::string line; std::getline(in, line);) {
    if (line.find("B U C K L I N G   F A C T O R") != std::string::npos) {
      block = true, factors->clear();
      continue;
    }
    if (!block) continue;
    std::istringstream row(line);
    int mode = 0;
    double factor = 0.0;
    if (row >> mode >> factor) factors->push_back(factor);
    else if (!factors->empty()) block = false;  // the block ends at the first line after its rows
  }
  if (factors->empty()) return Status::InvalidInput("ccx .dat: no buckling factors");
  return Status::Ok();
}

}  // namespace pqlayout
