// cgal_compare: CGAL 5.x's fixed-border parameterizers (Discrete conformal
// map, Discrete authalic) and LSCM against ours, on the same generated
// meshes in the same run. Benchmark-only: the library never needs CGAL.
//
// Same boundary: CGAL's Circular_border_arc_length_parameterizer_3 walks the
// border half-edges from the source of the given one, placing each vertex at
// angle -2 pi s / L (s the arc length walked) on the circle of radius 1/2
// around (1/2, 1/2). CGAL's border half-edges run against the faces, so in
// our loop direction (faces on the left) that is +2 pi t / L from the same
// start vertex: our arc-length circle, started at that vertex, in [0, 1]^2.
// We give exactly those positions, so the UVs must agree up to CGAL's
// iterative solver tolerance (its default is BiCGSTAB with ILUT).
//
// LSCM against our natural conformal map: the same two pins (our default,
// the outer-loop vertices farthest apart in 3D) at CGAL's Two_vertices
// positions (0, 1/2) and (1, 1/2), given to both. The maps are NOT the
// same: CGAL writes each triangle's equation as (Z1 - Z0)(U2 - U0) =
// (Z2 - Z0)(U1 - U0) without dividing by the triangle's size (its source
// says so, for stability), which weights each triangle's conformal energy
// by its area once more than LSCM / the natural conformal map do. On our
// irregular patches (denser on one side) the layouts differ by about 1e-2;
// the column is printed so that difference stays visible. The time ratio
// compares two least-squares problems of the same size and sparsity.
//
//   cgal_compare [--sizes 150000,300000] [--methods conformal,authalic,lscm]
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh_parameterization/Circular_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_authalic_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_conformal_map_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Two_vertices_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "intrinsic/generate.h"
#include "intrinsic/parameterize.h"

namespace SMP = CGAL::Surface_mesh_parameterization;
using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using VertexIndex = SurfaceMesh::Vertex_index;
using HalfedgeIndex = SurfaceMesh::Halfedge_index;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

struct CgalRun {
  double seconds = 0;
  bool ok = false;
  intrinsic::MatrixX2d UV;
};

template <class Parameterizer>
CgalRun run_cgal(SurfaceMesh& sm, HalfedgeIndex bhd, Parameterizer param) {
  auto uvmap = sm.add_property_map<VertexIndex, Kernel::Point_2>("v:uv").first;
  const auto t0 = Clock::now();
  const SMP::Error_code err = SMP::parameterize(sm, param, bhd, uvmap);
  CgalRun r;
  r.seconds = seconds_since(t0);
  r.ok = err == SMP::OK;
  r.UV.resize(sm.number_of_vertices(), 2);
  for (VertexIndex v : sm.vertices()) r.UV.row(v.idx()) << uvmap[v].x(), uvmap[v].y();
  sm.remove_property_map(uvmap);
  return r;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes = {150000};
  std::vector<std::string> methods = {"conformal", "authalic", "lscm"};
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--sizes") {
      sizes.clear();
      for (const std::string& s : split(argv[i + 1])) sizes.push_back(std::stoi(s));
    } else if (a == "--methods") {
      methods = split(argv[i + 1]);
    }
  }
  std::cout << "| V | method | CGAL s | ours (parameterize) s | ratio | ours end to end s* | max UV diff |\n"
               "|---|---|---|---|---|---|---|\n";
  for (int n : sizes) {
    intrinsic::GenerateOptions g;
    g.rings = std::max(2, static_cast<int>(std::lround(std::sqrt(n / 3.0))));
    const intrinsic::MeshData data = intrinsic::generate_wavy_patch(g);
    const auto tv = Clock::now();
    const intrinsic::Mesh mesh = intrinsic::make_mesh(data);
    const double validate_s = seconds_since(tv);

    SurfaceMesh sm;
    for (int v = 0; v < mesh.V.rows(); ++v) sm.add_vertex(Kernel::Point_3(mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2)));
    for (int f = 0; f < mesh.F.rows(); ++f)
      sm.add_face(VertexIndex(mesh.F(f, 0)), VertexIndex(mesh.F(f, 1)), VertexIndex(mesh.F(f, 2)));
    const HalfedgeIndex bhd = CGAL::Polygon_mesh_processing::longest_border(sm).first;

    // Our circle from CGAL's start vertex, in [0, 1]^2.
    const std::vector<int>& loop = mesh.topology.boundary_loops[mesh.topology.component_loops[0][0]];
    const int start = static_cast<int>(sm.source(bhd).idx());
    std::vector<int> rotated(loop.size());
    size_t s0 = 0;
    while (loop[s0] != start) ++s0;
    for (size_t k = 0; k < loop.size(); ++k) rotated[k] = loop[(s0 + k) % loop.size()];
    const std::vector<double> t = intrinsic::loop_parameters(mesh.V, rotated, intrinsic::Spacing::ArcLength);

    for (const std::string& method : methods) {
      CgalRun c;
      double ours = 0, diff = 0;
      bool have_ours = false;
      if (method == "conformal") {
        c = run_cgal(sm, bhd, SMP::Discrete_conformal_map_parameterizer_3<SurfaceMesh>());
      } else if (method == "authalic") {
        c = run_cgal(sm, bhd, SMP::Discrete_authalic_parameterizer_3<SurfaceMesh>());
      } else if (method == "lscm") {
        // Our default pins, found by a natural-map run (its time not counted).
        intrinsic::ParamOptions probe;
        probe.boundary = intrinsic::BoundaryShape::Natural;
        const intrinsic::ParamResult p = intrinsic::parameterize(mesh, probe);
        const int a = p.pins.at(0).vertex, b = p.pins.at(1).vertex;
        using Border = SMP::Two_vertices_parameterizer_3<SurfaceMesh>;
        c = run_cgal(sm, bhd, SMP::LSCM_parameterizer_3<SurfaceMesh, Border>(Border(VertexIndex(a), VertexIndex(b))));
        intrinsic::ParamOptions o;
        o.boundary = intrinsic::BoundaryShape::Natural;
        o.pins = {{a, Eigen::Vector2d(0, 0.5)}, {b, Eigen::Vector2d(1, 0.5)}};
        const auto t0 = Clock::now();
        const intrinsic::ParamResult r = intrinsic::parameterize(mesh, o);
        ours = seconds_since(t0);
        diff = (r.UV - c.UV).cwiseAbs().maxCoeff();
        have_ours = true;
      } else {
        std::cerr << "unknown method " << method << "\n";
        return 2;
      }
      if (method != "lscm") {
        intrinsic::ParamOptions o;
        o.weights.method = intrinsic::parse_method(method);
        o.boundary = intrinsic::BoundaryShape::Given;
        for (size_t k = 0; k < rotated.size(); ++k) {
          const double a = 2 * M_PI * t[k];
          o.given.push_back({rotated[k], Eigen::Vector2d(0.5 + 0.5 * std::cos(a), 0.5 + 0.5 * std::sin(a))});
        }
        const auto t0 = Clock::now();
        const intrinsic::ParamResult r = intrinsic::parameterize(mesh, o);
        ours = seconds_since(t0);
        diff = (r.UV - c.UV).cwiseAbs().maxCoeff();
        have_ours = true;
      }
      char line[256];
      if (have_ours)
        std::snprintf(line, sizeof line, "| %d | %s | %.2f%s | %.3f | %.0fx | %.3f | %.1e |", static_cast<int>(mesh.V.rows()),
                      method == "lscm" ? "LSCM vs natural" : method.c_str(), c.seconds, c.ok ? "" : " (failed)", ours, c.seconds / ours, ours + validate_s, diff);
      else
        std::snprintf(line, sizeof line, "| %d | %s | %.2f%s | (natural map: not wired into this comparison yet) | | | |",
                      static_cast<int>(mesh.V.rows()), method.c_str(), c.seconds, c.ok ? "" : " (failed)");
      std::cout << line << std::endl;
    }
  }
  std::cout << "\n*ours end to end here = validate + parameterize (the mesh is in memory for both; CGAL's time is its "
               "parameterize call on a built Surface_mesh).\n";
  return 0;
}
