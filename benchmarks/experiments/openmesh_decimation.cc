// Not built by CMake: OpenMesh's decimaters on the 968k Great Court reference (see
// cgal_decimation.cc for how to write it), measured on 2026-12-03. Mode 0: edge-length
// module down to PRE metres; mode 1: quadric module down to FACES faces. Define MC for the
// multiple-choice decimater (McDecimaterT). Reproduce:
//   g++ -O2 -DNDEBUG -std=c++17 [-DMC] benchmarks/experiments/openmesh_decimation.cc -o /tmp/om -lOpenMeshCore -lOpenMeshTools
//   /tmp/om /tmp/gc968/surface.obj 0 0.4 60000
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/McDecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <OpenMesh/Tools/Decimater/ModEdgeLengthT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <chrono>
#include <iostream>
struct T : OpenMesh::DefaultTraits { typedef OpenMesh::Vec3d Point; typedef OpenMesh::Vec3d Normal; };
typedef OpenMesh::TriMesh_ArrayKernelT<T> Mesh;
double now(){return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();}
int main(int argc,char**argv){
  Mesh m; OpenMesh::IO::read_mesh(m, argv[1]);
  int mode=atoi(argv[2]); double pre=atof(argv[3]);
  double t0=now();
  m.request_vertex_status(); m.request_edge_status(); m.request_face_status(); m.request_face_normals(); m.update_face_normals();
  for(auto v:m.vertices()) if(m.is_boundary(v)) m.status(v).set_locked(true);
  #ifdef MC
  OpenMesh::Decimater::McDecimaterT<Mesh> d(m);
#else
  OpenMesh::Decimater::DecimaterT<Mesh> d(m);
#endif
  if(mode==0){ OpenMesh::Decimater::ModEdgeLengthT<Mesh>::Handle h; d.add(h); d.module(h).set_edge_length(pre); d.module(h).set_binary(false);}
  else { OpenMesh::Decimater::ModQuadricT<Mesh>::Handle h; d.add(h); d.module(h).set_binary(false);}
  OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle nf; d.add(nf); d.module(nf).set_max_normal_deviation(30);
  d.initialize();
  #ifdef MC
  size_t n = d.decimate_to_faces(0, atoi(argv[4]));
#else
  size_t n = mode==0 ? d.decimate() : d.decimate_to_faces(0, atoi(argv[4]));
#endif
  m.garbage_collection();
  std::cout<<"removed "<<n<<" faces "<<m.n_faces()<<" in "<<now()-t0<<" s\n";
  OpenMesh::IO::write_mesh(m, "om.obj");
}
