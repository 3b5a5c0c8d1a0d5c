// Not built by CMake: the decimation measured on 2026-12-03 before geometry/plan_remesh.h was
// written (benchmarks/RESULTS.md, "The working mesh from the plan"). Times CGAL's isotropic
// remeshing of a reference to a 1.2 m edge (mode 0), or CGAL's edge_collapse with edge-length
// cost down to PRE metres first (mode 1). Reproduce:
//   build/cli/pqlayout run examples/great_court.yaml --set surface.edge_length=0.17 --until surface --out /tmp/gc968
//   g++ -O2 -DNDEBUG -std=c++17 benchmarks/experiments/cgal_decimation.cc -o /tmp/cgal_decimation -lgmp -lmpfr
//   /tmp/cgal_decimation /tmp/gc968/surface.obj 0 0; /tmp/cgal_decimation /tmp/gc968/surface.obj 1 0.4
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Edge_length_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Midpoint_placement.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Edge_length_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_placement.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <chrono>
#include <iostream>
typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> M;
namespace PMP = CGAL::Polygon_mesh_processing;
namespace SMS = CGAL::Surface_mesh_simplification;
double now(){return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();}
int main(int argc,char**argv){
  M mesh; PMP::IO::read_polygon_mesh(argv[1], mesh);
  int mode=atoi(argv[2]); double L=1.2; double pre=atof(argv[3]);
  std::cout<<"faces "<<mesh.number_of_faces()<<"\n";
  double t0=now();
  if(mode==1){
    auto c = mesh.add_property_map<M::Edge_index,bool>("e:c",false).first;
    for(auto e:mesh.edges()) c[e]=mesh.is_border(e);
    SMS::Edge_length_stop_predicate<double> stop(pre);
    int r = SMS::edge_collapse(mesh, stop, CGAL::parameters::edge_is_constrained_map(c)
        .get_cost(SMS::Edge_length_cost<M>()).get_placement(SMS::Bounded_normal_change_placement<SMS::Midpoint_placement<M>>()));
    mesh.collect_garbage();
    std::cout<<"sms removed "<<r<<" -> faces "<<mesh.number_of_faces()<<" in "<<now()-t0<<" s\n";
  }
  double t1=now();
  auto constrained = mesh.add_property_map<M::Edge_index, bool>("e:constrained", false).first;
  for (auto e : mesh.edges()) constrained[e] = mesh.is_border(e);
  PMP::isotropic_remeshing(faces(mesh), L, mesh, PMP::parameters::number_of_iterations(3).edge_is_constrained_map(constrained)
     .protect_constraints(false).collapse_constraints(true).relax_constraints(true));
  mesh.collect_garbage();
  std::cout<<"iso -> faces "<<mesh.number_of_faces()<<" in "<<now()-t1<<" s; total "<<now()-t0<<"\n";
  CGAL::IO::write_polygon_mesh(std::string("out")+argv[2]+".off", mesh);
}
