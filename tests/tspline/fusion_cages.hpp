#pragma once
// Quad cages written as Autodesk Fusion 360 writes TSM files (its settings, no grip map, every vertex NORTH), the
// check that a triangulation is a closed two-manifold, and the command line run on such files.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "star_mesh_tsm.hpp"
#include "support/temp_dir.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/t_spline_tessellation.hpp"

namespace trivar::test {

// A quad cage in Fusion's form: links per face in order, an outside link for every boundary edge (its corner flag
// the outside's angle / 90 - 1 at its start), every interval `interval`, and the settings and tail Fusion writes.
inline std::string fusion_text(const QuadMesh& m, const std::string& end_conditions = "SUBD_CREASES", double interval = 1.0,
                        const std::string& extra = "") {
  struct Link {
    int prev, next, opp = -1, vertex, face, edge = -1, flag = 0;
  };
  std::vector<Link> links;
  std::map<std::array<int, 2>, int> by_ends;
  std::vector<int> faces_at(m.points.size(), 0);
  for (int f = 0; f < static_cast<int>(m.quads.size()); ++f)
    for (int k = 0; k < 4; ++k) {
      const int l = static_cast<int>(links.size());
      links.push_back({4 * f + (k + 3) % 4, 4 * f + (k + 1) % 4, -1, m.quads[f][k], f});
      by_ends[{m.quads[f][k], m.quads[f][(k + 1) % 4]}] = l;
      ++faces_at[m.quads[f][k]];
    }
  const int inner = static_cast<int>(links.size());
  std::map<int, int> outside_from;
  for (int l = 0; l < inner; ++l) {
    const int a = links[l].vertex, b = links[links[l].next].vertex;
    if (auto it = by_ends.find({b, a}); it != by_ends.end()) {
      links[l].opp = it->second;
      continue;
    }
    links[l].opp = static_cast<int>(links.size());
    outside_from[b] = static_cast<int>(links.size());
    links.push_back({-1, -1, l, b, -1, -1, 3 - faces_at[b]});
  }
  for (int o = inner; o < static_cast<int>(links.size()); ++o) {
    const int to = links[links[o].opp].vertex;
    links[o].next = outside_from.at(to);
    links[outside_from.at(to)].prev = o;
  }
  std::vector<int> edge_link;
  for (int l = 0; l < static_cast<int>(links.size()); ++l)
    if (links[l].edge < 0) {
      links[l].edge = links[links[l].opp].edge = static_cast<int>(edge_link.size());
      edge_link.push_back(l);
    }
  std::vector<int> vertex_link(m.points.size(), -1);
  for (int l = 0; l < static_cast<int>(links.size()); ++l)
    if (vertex_link[links[l].vertex] < 0) vertex_link[links[l].vertex] = l;
  std::ostringstream os;
  os.precision(17);
  os << "#TS0200\n\ndegree 3\ncap-type G1CAPS\nstar-smoothness 0\nunits 1 meters\nend-conditions " << end_conditions
     << "\nstar-knot-rule NURCCS\n";
  for (std::size_t f = 0; f < m.quads.size(); ++f) os << "f " << 4 * f << " 0\n";
  for (int l : edge_link) os << "e " << l << ' ' << interval << '\n';
  for (int l : vertex_link) os << "v " << l << " NORTH\n";
  for (const Link& k : links)
    os << "l " << k.prev << ' ' << k.next << ' ' << k.opp << ' ' << k.vertex << ' ' << k.face << ' ' << k.edge << ' ' << k.flag << '\n';
  for (const auto& p : m.points) os << "0g " << p[0] << ' ' << p[1] << ' ' << p[2] << " 1\n";
  os << extra << "\ntol 1.00000000000000008e-05\ngeom-tol 1.00000000000000008e-05\nver 992\nbehavior-version 14.2.0\n"
     << "compat-version 13.3.0\n";
  return os.str();
}

// The cage as Fusion writes it (SUBD_CREASES) with the edges `crease` picks in its crease list `100edges` and the
// vertices `creased` in `100verts` (parsed once without them for the edge numbers).
template <class Crease>
std::string fusion_creased_text(const QuadMesh& cage, const Crease& crease, const std::vector<int>& creased = {}) {
  const TMesh plain = io::parse_tsm(fusion_text(cage), "plain.tsm").mesh;
  std::set<int> edges;
  for (const TMeshLink& k : plain.links)
    if (k.vertex >= 0 && crease(k.vertex, plain.links[static_cast<std::size_t>(k.opp)].vertex)) edges.insert(k.edge);
  std::string lists = "100edges";
  for (int e : edges) lists += " " + std::to_string(e);
  lists += "\n100verts";
  for (int v : creased) lists += " " + std::to_string(v);
  return fusion_text(cage, "SUBD_CREASES", 1.0, lists + "\n");
}

// The torus cage of nu x nv vertices, vertex (i, j) = i * nv + j, face (i, j) from vertex (i, j) along i, then j.
inline QuadMesh torus_cage(int nu, int nv) {
  QuadMesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double a = 2 * std::numbers::pi * i / nu, b = 2 * std::numbers::pi * j / nv;
      // A little unevenness, so that no symmetry hides a wrong wrap.
      const double r = 6 + 0.7 * std::sin(3.0 * a + b);
      m.points.push_back({(20 + r * std::cos(b)) * std::cos(a), (20 + r * std::cos(b)) * std::sin(a), r * std::sin(b)});
    }
  const auto id = [&](int i, int j) { return ((i % nu + nu) % nu) * nv + (j % nv + nv) % nv; };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) m.quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return m;
}

// An open grid of nx x ny faces in the plane z = height(x, y), vertex (i, j) = j * (nx + 1) + i.
inline QuadMesh grid_cage(int nx, int ny) {
  QuadMesh m;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.points.push_back({1.0 * i, 1.3 * j, std::sin(1.0 + i - 0.5 * j) + 0.1 * i * j});
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i;
      m.quads.push_back({a, a + 1, a + nx + 2, a + nx + 1});
    }
  return m;
}

// The triangles of an OBJ file (vertices counted, faces of three vertex numbers).
inline TSplineTriangulation obj_triangles(const std::string& path) {
  std::ifstream obj(path);
  TSplineTriangulation t;
  for (std::string line; std::getline(obj, line);) {
    std::istringstream ls(line);
    std::string kind;
    ls >> kind;
    if (kind == "v") t.points.push_back({});
    if (kind != "f") continue;
    std::array<int, 3> tri{};
    for (int& x : tri) {
      std::string w;
      ls >> w;
      x = std::stoi(w) - 1;
    }
    t.triangles.push_back(tri);
  }
  return t;
}

// The command line with `args`, its output (stdout and stderr) in dir; a non-zero exit fails the test.
inline std::string run_cli(const TempDir& dir, const std::string& args) {
  const std::string out = dir.file("out.txt");
  const int rc = std::system((std::string(TRIVAR_CLI_PATH) + " " + args + " > " + out + " 2>&1").c_str());
  std::ifstream in(out);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_EQ(rc, 0) << args << "\n" << ss.str();
  return ss.str();
}

// The point `trivar eval FILE FACE U V` prints for a face as given ("S   = x y z"; NaN when it prints none).
inline std::array<double, 3> cli_face_point(const TempDir& dir, const std::string& file, int face, double u, double v) {
  std::ostringstream args;
  args << "eval " << file << ' ' << face << ' ' << u << ' ' << v;
  const std::string out = run_cli(dir, args.str());
  std::istringstream printed(out.substr(std::min(out.size(), out.find("S   = ") + 6)));
  std::array<double, 3> p{NAN, NAN, NAN};
  printed >> p[0] >> p[1] >> p[2];
  return p;
}

}  // namespace trivar::test
