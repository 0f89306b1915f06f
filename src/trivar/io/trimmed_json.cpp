#include "trivar/io/trimmed_json.hpp"

#include <algorithm>

#include "trivar/core/error.hpp"
#include "trivar/io/json_format.hpp"

namespace trivar::io {

namespace {

using json = nlohmann::json;

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw Error(where + ": " + what); }

const json& member(const json& j, const char* key, const std::string& where) {
  if (!j.is_object()) fail(where, std::string("expected an object, got ") + j.type_name());
  const auto it = j.find(key);
  if (it == j.end()) fail(where, std::string("missing key \"") + key + "\"");
  return *it;
}

const json& array(const json& j, const char* key, const std::string& where) {
  const json& a = member(j, key, where);
  if (!a.is_array()) fail(where + ": " + key, std::string("expected an array, got ") + a.type_name());
  return a;
}

template <int D>
json spline_json(const TensorSpline<D>& s) {
  json j = to_json(AnySpline(s));
  j.erase("trivar");
  return j;
}

template <int D>
TensorSpline<D> spline_of(json j, int dim, const std::string& where) {
  if (j.is_object() && !j.contains("trivar")) j["trivar"] = 1;
  AnySpline s = spline_from_json(j, where);
  if (parametric_dimension(s) != D) fail(where, D == 1 ? "expected a curve" : "expected a surface");
  TensorSpline<D> t = std::get<TensorSpline<D>>(std::move(s));
  if (t.dim() != dim) fail(where, "expected control dimension " + std::to_string(dim) + ", got " + std::to_string(t.dim()));
  return t;
}

template <class T>
std::vector<T> numbers(const json& j, const char* key, std::size_t multiple, const std::string& where) {
  const json& a = array(j, key, where);
  std::vector<T> v;
  v.reserve(a.size());
  for (const json& x : a) {
    if (!x.is_number()) fail(where + ": " + key, "expected numbers");
    v.push_back(x.get<T>());
  }
  if (v.size() % multiple != 0) fail(where + ": " + key, "expected a multiple of " + std::to_string(multiple) + " numbers");
  return v;
}

double number(const json& j, const char* key, const std::string& where) {
  const json& x = member(j, key, where);
  if (!x.is_number()) fail(where + ": " + key, "expected a number");
  return x.get<double>();
}

bool boolean(const json& j, const char* key, const std::string& where) {
  const json& x = member(j, key, where);
  if (!x.is_boolean()) fail(where + ": " + key, "expected true or false");
  return x.get<bool>();
}

std::string text(const json& j, const char* key) { return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : ""; }

}  // namespace

json to_json(const TrimmedBoundary& b) {
  json faces = json::array();
  for (const TrimmedFace& f : b.faces) {
    json loops = json::array();
    for (const TrimLoop& l : f.loops) {
      json curves = json::array();
      for (const TrimCurve& c : l.curves)
        curves.push_back({{"pcurve", spline_json(c.pcurve)}, {"edge", c.edge}, {"edge_reversed", c.edge_reversed}});
      loops.push_back(std::move(curves));
    }
    faces.push_back({{"surface", spline_json(f.surface)}, {"reversed", f.reversed}, {"tolerance", f.tolerance},
                     {"kind", f.kind}, {"name", f.name}, {"loops", std::move(loops)}});
  }
  json edges = json::array();
  for (const TrimEdge& e : b.edges)
    edges.push_back(e.curve.num_coefs() > 0 ? json{{"curve", spline_json(e.curve)}, {"tolerance", e.tolerance}} : json());
  std::vector<double> vertices, uv;
  std::vector<int> triangles;
  for (const auto& v : b.mesh.vertices) vertices.insert(vertices.end(), v.begin(), v.end());
  for (const auto& t : b.mesh.triangles) triangles.insert(triangles.end(), t.begin(), t.end());
  for (const auto& t : b.triangle_uv)
    for (const auto& p : t) uv.insert(uv.end(), p.begin(), p.end());
  return {{"chordal_tolerance", b.chordal_tolerance},
          {"faces", std::move(faces)},
          {"edges", std::move(edges)},
          {"mesh", {{"vertices", vertices}, {"triangles", triangles}, {"triangle_face", b.triangle_face}, {"triangle_uv", uv}}}};
}

TrimmedBoundary trimmed_boundary_from_json(const json& j, const std::string& where) {
  TrimmedBoundary b;
  b.chordal_tolerance = number(j, "chordal_tolerance", where);
  if (!(b.chordal_tolerance >= 0)) fail(where + ": chordal_tolerance", "expected a number >= 0");
  const json& faces = array(j, "faces", where);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const std::string at = where + ": faces[" + std::to_string(i) + "]";
    const json& f = faces[i];
    TrimmedFace face;
    face.surface = spline_of<2>(member(f, "surface", at), 3, at + ": surface");
    face.reversed = boolean(f, "reversed", at);
    face.tolerance = number(f, "tolerance", at);
    face.kind = text(f, "kind");
    face.name = text(f, "name");
    const json& loops = array(f, "loops", at);
    for (std::size_t l = 0; l < loops.size(); ++l) {
      const std::string lat = at + ": loops[" + std::to_string(l) + "]";
      if (!loops[l].is_array()) fail(lat, "expected an array of trimming curves");
      TrimLoop loop;
      for (std::size_t c = 0; c < loops[l].size(); ++c) {
        const std::string cat = lat + "[" + std::to_string(c) + "]";
        const json& cj = loops[l][c];
        TrimCurve tc;
        tc.pcurve = spline_of<1>(member(cj, "pcurve", cat), 2, cat + ": pcurve");
        const json& e = member(cj, "edge", cat);
        if (!e.is_number_integer()) fail(cat + ": edge", "expected an integer");
        tc.edge = e.get<int>();
        tc.edge_reversed = boolean(cj, "edge_reversed", cat);
        loop.curves.push_back(std::move(tc));
      }
      face.loops.push_back(std::move(loop));
    }
    b.faces.push_back(std::move(face));
  }
  const json& edges = array(j, "edges", where);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const std::string at = where + ": edges[" + std::to_string(i) + "]";
    TrimEdge e;
    if (!edges[i].is_null()) {
      e.curve = spline_of<1>(member(edges[i], "curve", at), 3, at + ": curve");
      e.tolerance = number(edges[i], "tolerance", at);
    }
    b.edges.push_back(std::move(e));
  }
  const std::string mat = where + ": mesh";
  const json& mesh = member(j, "mesh", where);
  const auto v = numbers<double>(mesh, "vertices", 3, mat);
  const auto t = numbers<long long>(mesh, "triangles", 3, mat);
  const auto tf = numbers<long long>(mesh, "triangle_face", 1, mat);
  const auto uv = numbers<double>(mesh, "triangle_uv", 6, mat);
  const std::size_t nt = t.size() / 3;
  if (tf.size() != nt || uv.size() != 6 * nt) fail(mat, "expected one face and three (u, v) pairs per triangle");
  for (std::size_t i = 0; i < v.size(); i += 3) b.mesh.vertices.push_back({v[i], v[i + 1], v[i + 2]});
  const auto nv = static_cast<long long>(b.mesh.vertices.size()), nf = static_cast<long long>(b.faces.size());
  for (std::size_t i = 0; i < nt; ++i) {
    std::array<int, 3> tri;
    for (int k = 0; k < 3; ++k) {
      const long long id = t[3 * i + k];
      if (id < 0 || id >= nv) fail(mat + ": triangles", "vertex index " + std::to_string(id) + " out of range");
      tri[k] = static_cast<int>(id);
    }
    if (tf[i] < 0 || tf[i] >= nf) fail(mat + ": triangle_face", "face index " + std::to_string(tf[i]) + " out of range");
    b.mesh.triangles.push_back(tri);
    b.triangle_face.push_back(static_cast<int>(tf[i]));
    b.triangle_uv.push_back({Param<2>{uv[6 * i], uv[6 * i + 1]}, Param<2>{uv[6 * i + 2], uv[6 * i + 3]},
                             Param<2>{uv[6 * i + 4], uv[6 * i + 5]}});
  }
  return b;
}

}  // namespace trivar::io
