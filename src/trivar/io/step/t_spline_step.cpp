#include "trivar/io/step/t_spline_step.hpp"

#include <algorithm>
#include <unordered_map>

#include "trivar/core/error.hpp"
#include "trivar/io/step/geometry_writer.hpp"
#include "trivar/io/step/writer.hpp"
#include "trivar/tspline/classification.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar::io::step {

namespace {

constexpr std::array<std::string_view, 11> kKeywords{"T_SPLINE_SURFACE", "T_IMAGE", "T_CONNECT", "T_POINTSET",
                                                    "T_VERTEX",         "T_EDGE",  "T_LINK",    "T_FACE",
                                                    "T_EDGE_CONDITION", "T_NODE_V4", "T_NODE"};
constexpr std::array<std::string_view, 4> kParts{"RATIONAL_POINT", "EDGE_LOOP", "FACE_BOUND", "POINT_ON_SURFACE"};

Parameter logical(bool b) { return enumeration(b ? "T" : "F"); }

Parameter ref_or_unset(int index, std::uint64_t first) {
  return index < 0 ? Parameter(Unset{}) : reference(first + static_cast<std::uint64_t>(index));
}

std::vector<Parameter> refs(std::size_t n, std::uint64_t first) {
  std::vector<Parameter> r;
  for (std::size_t i = 0; i < n; ++i) r.push_back(reference(first + i));
  return r;
}

// Reads one T_SPLINE_SURFACE: typed access with one-line errors naming the instance.
class Mapper {
public:
  Mapper(const ExchangeFile& f, std::string name) : f_(f), name_(std::move(name)) {}

  TSpline map(const Instance& top) const;

private:
  const ExchangeFile& f_;
  std::string name_;

  [[noreturn]] void fail(const Instance& in, const std::string& msg) const {
    throw Error(name_ + ":" + std::to_string(in.line) + ":" + std::to_string(in.column) + ": #" +
                std::to_string(in.id) + ": " + in.type_name() + ": " + msg);
  }
  const std::vector<Parameter>& params(const Instance& in, std::size_t n) const {
    if (in.records.size() != 1) fail(in, "expected a simple instance");
    const auto& p = in.records.front().params;
    if (p.size() != n) fail(in, std::to_string(p.size()) + " parameters, expected " + std::to_string(n));
    return p;
  }
  const Instance& deref(const Instance& from, const Parameter& p, std::initializer_list<std::string_view> kinds,
                        const std::string& what) const {
    const Reference* r = p.get_if<Reference>();
    if (!r) fail(from, what + ": expected a reference, found a " + kind_name(p.kind()));
    const Instance* in = f_.find(r->id);
    if (!in) fail(from, what + ": #" + std::to_string(r->id) + " is not an instance of the file");
    for (std::string_view k : kinds)
      if (in->is(k)) return *in;
    fail(from, what + ": #" + std::to_string(r->id) + " is a " + in->type_name() + ", expected a " + std::string(*kinds.begin()));
  }
  const std::vector<Parameter>& list(const Instance& from, const Parameter& p, const std::string& what) const {
    const List* l = p.get_if<List>();
    if (!l) fail(from, what + ": expected a list, found a " + kind_name(p.kind()));
    return l->items;
  }
  double number(const Instance& from, const Parameter& p, const std::string& what) const {
    const auto v = p.number();
    if (!v) fail(from, what + ": expected a number, found a " + kind_name(p.kind()));
    return *v;
  }
  bool logical_value(const Instance& from, const Parameter& p, const std::string& what) const {
    const auto v = p.boolean();
    if (!v) fail(from, what + ": expected .T. or .F.");
    return *v;
  }
  // The ids of a list of references to instances of one kind, and their positions.
  std::unordered_map<std::uint64_t, int> index(const Instance& from, const Parameter& p, std::string_view kind,
                                               const std::string& what, std::vector<const Instance*>& out) const {
    std::unordered_map<std::uint64_t, int> ix;
    for (const Parameter& q : list(from, p, what)) {
      const Instance& in = deref(from, q, {kind}, what);
      if (!ix.emplace(in.id, static_cast<int>(out.size())).second) fail(from, what + ": #" + std::to_string(in.id) + " listed twice");
      out.push_back(&in);
    }
    return ix;
  }
  int member(const Instance& from, const Parameter& p, const std::unordered_map<std::uint64_t, int>& ix,
             const std::string& what, bool optional) const {
    if (optional && p.kind() == Kind::unset) return -1;
    const Reference* r = p.get_if<Reference>();
    if (!r) fail(from, what + ": expected a reference");
    auto it = ix.find(r->id);
    if (it == ix.end()) fail(from, what + ": #" + std::to_string(r->id) + " is not one of this T-spline's entities");
    return it->second;
  }
};

TSpline Mapper::map(const Instance& top) const {
  TSpline ts;
  const auto& P = params(top, 7);
  if (const std::string* s = P[0].get_if<std::string>()) ts.name = *s;
  for (int k = 0; k < 2; ++k) {
    const auto* d = P[static_cast<std::size_t>(1 + k)].get_if<std::int64_t>();
    if (!d || *d < 1 || *d > 31) fail(top, std::string("degree_") + (k == 0 ? "s" : "t") + ": expected an integer in 1..31");
    ts.degrees[k] = static_cast<int>(*d);
  }
  logical_value(top, P[3], "rational");
  const Instance& image = deref(top, P[4], {"T_IMAGE"}, "t_image");
  const Instance& connect = deref(top, P[5], {"T_CONNECT"}, "t_connect");
  const Instance& pointset = deref(top, P[6], {"T_POINTSET"}, "t_pointset");

  const auto& I = params(image, 5);
  std::vector<const Instance*> F, L, E, V, N, Q;
  const auto face_ix = index(image, I[1], "T_FACE", "faces", F);
  const auto link_ix = index(image, I[2], "T_LINK", "links", L);
  const auto edge_ix = index(image, I[3], "T_EDGE", "edges", E);
  const auto vertex_ix = index(image, I[4], "T_VERTEX", "vertices", V);
  const auto& C = params(connect, 2);
  std::vector<const Instance*> nodes_in;
  std::unordered_map<std::uint64_t, int> node_ix;
  for (const Parameter& q : list(connect, C[1], "nodes")) {
    const Instance& in = deref(connect, q, {"T_NODE_V4", "T_NODE"}, "nodes");
    if (!node_ix.emplace(in.id, static_cast<int>(nodes_in.size())).second) fail(connect, "nodes: listed twice");
    nodes_in.push_back(&in);
  }
  const auto& S = params(pointset, 2);
  const auto point_ix = index(pointset, S[1], "RATIONAL_POINT", "points", Q);

  TImage& im = ts.image;
  for (const Instance* v : V) {
    const auto& p = params(*v, 6);
    const Instance& pos = deref(*v, p[1], {"POINT_ON_SURFACE"}, "parameter");
    const auto& pp = params(pos, 4);
    TVertex x;
    x.s = number(pos, pp[2], "point_parameter_u");
    x.t = number(pos, pp[3], "point_parameter_v");
    for (int d = 0; d < 4; ++d)
      x.links[static_cast<std::size_t>(d)] = member(*v, p[static_cast<std::size_t>(2 + d)], link_ix, kTDirNames[static_cast<std::size_t>(d)], true);
    im.vertices.push_back(x);
  }
  for (const Instance* e : E) {
    const auto& p = params(*e, 6);
    im.edges.push_back({member(*e, p[1], vertex_ix, "start", false), member(*e, p[2], vertex_ix, "end", false)});
  }
  for (const Instance* l : L) {
    const auto& p = params(*l, 5);
    im.links.push_back({member(*l, p[3], edge_ix, "edge", false), logical_value(*l, p[4], "sense")});
  }
  for (const Instance* fc : F) {
    const auto& p = params(*fc, 2);
    const auto& bounds = list(*fc, p[1], "bounds");
    if (bounds.size() != 1) fail(*fc, "expected one FACE_BOUND (a T-face is a rectangle without holes)");
    const Instance& b = deref(*fc, bounds[0], {"FACE_BOUND"}, "bound");
    const auto& bp = params(b, 3);
    if (!logical_value(b, bp[2], "orientation")) fail(b, "orientation .F. (T-face loops run counter-clockwise)");
    const Instance& loop = deref(b, bp[1], {"EDGE_LOOP"}, "bound");
    const auto& lp = params(loop, 2);
    TFace face;
    for (const Parameter& q : list(loop, lp[1], "edge_list")) face.loop.push_back(member(loop, q, link_ix, "edge_list", false));
    im.faces.push_back(std::move(face));
  }
  for (const Instance& in : f_.instances())
    if (in.is("T_EDGE_CONDITION")) {
      const auto& p = params(in, 3);
      const Reference* r = p[1].get_if<Reference>();
      if (!r || !edge_ix.count(r->id)) continue;  // a condition of another T-spline
      im.conditions.push_back({edge_ix.at(r->id), logical_value(in, p[2], "flag")});
    }
  for (const Instance* q : Q) {
    const auto& p = params(*q, 3);
    const auto& xyz = list(*q, p[1], "coordinates");
    if (xyz.size() != 3) fail(*q, "coordinates: expected 3 values");
    ts.pointset.points.push_back({{number(*q, xyz[0], "x"), number(*q, xyz[1], "y"), number(*q, xyz[2], "z")},
                                  number(*q, p[2], "weight")});
  }
  for (const Instance* n : nodes_in) {
    const auto& p = params(*n, 7);
    TNode x;
    const Instance& a = deref(*n, p[1], {"T_VERTEX", "T_LINK", "T_FACE"}, "anchor");
    if (a.is("T_VERTEX")) {
      x.kind = TAnchorKind::vertex;
      x.anchor = member(*n, p[1], vertex_ix, "anchor", false);
    } else if (a.is("T_LINK")) {
      x.kind = TAnchorKind::link;
      x.anchor = member(*n, p[1], link_ix, "anchor", false);
    } else {
      x.kind = TAnchorKind::face;
      x.anchor = member(*n, p[1], face_ix, "anchor", false);
    }
    x.point = member(*n, p[2], point_ix, "point", false);
    for (int d = 0; d < 4; ++d)
      x.neighbours[static_cast<std::size_t>(d)] = member(*n, p[static_cast<std::size_t>(3 + d)], node_ix, kTDirNames[static_cast<std::size_t>(d)], true);
    ts.connect.nodes.push_back(x);
  }
  // Edges from the larger to the smaller parameter are turned round with their links.
  for (std::size_t e = 0; e < im.edges.size(); ++e) {
    TEdge& x = im.edges[e];
    const TVertex& a = im.vertices[static_cast<std::size_t>(x.start)];
    const TVertex& b = im.vertices[static_cast<std::size_t>(x.end)];
    if (a.s > b.s || a.t > b.t) {
      std::swap(x.start, x.end);
      for (TLink& l : im.links)
        if (l.edge == static_cast<int>(e)) l.sense = !l.sense;
    }
  }
  try {
    validate(ts);
  } catch (const Error& e) {
    fail(top, e.what());
  }
  return ts;
}

std::uint64_t largest_id(const ExchangeFile& f) {
  std::uint64_t m = 0;
  for (const Instance& in : f.instances()) m = std::max(m, in.id);
  return m;
}

}  // namespace

bool is_t_spline_keyword(std::string_view k) { return std::find(kKeywords.begin(), kKeywords.end(), k) != kKeywords.end(); }

bool is_t_spline_part_keyword(std::string_view k) { return std::find(kParts.begin(), kParts.end(), k) != kParts.end(); }

bool is_t_spline_type(std::string_view t) {
  return t == "STANDARD_T_SPLINE" || t == "SEMI_STANDARD_T_SPLINE" || t == "ANALYSIS_SUITABLE_T_SPLINE";
}

std::uint64_t add_t_spline(ExchangeFile& f, const TSpline& ts, const std::string& name) {
  validate(ts);
  const TImage& im = ts.image;
  const std::size_t nv = im.vertices.size(), ne = im.edges.size(), nl = im.links.size(), nf = im.faces.size(),
                    nc = im.conditions.size(), nn = ts.connect.nodes.size(), np = ts.pointset.points.size();
  std::uint64_t next = largest_id(f);
  const auto take = [&](std::size_t n) {
    const std::uint64_t first = next + 1;
    next += n;
    return first;
  };
  const std::uint64_t surf = take(1), image = take(1), connect = take(1), pointset = take(1), pos0 = take(nv),
                      vert0 = take(nv), edge0 = take(ne), link0 = take(nl), cond0 = take(nc), loop0 = take(nf),
                      bound0 = take(nf), face0 = take(nf), node0 = take(nn), point0 = take(np);
  const auto put = [&](std::uint64_t id, std::string keyword, std::vector<Parameter> p) {
    Instance in;
    in.id = id;
    in.records.push_back({std::move(keyword), std::move(p)});
    f.insert(std::move(in));
  };
  const auto label = [](const char* prefix, std::size_t i) { return prefix + std::to_string(i + 1); };
  bool rational = false;
  for (const RationalPoint& p : ts.pointset.points) rational = rational || p.w != 1.0;
  put(surf, "T_SPLINE_SURFACE", {name, std::int64_t{ts.degrees[0]}, std::int64_t{ts.degrees[1]}, logical(rational),
                                 reference(image), reference(connect), reference(pointset)});
  put(image, "T_IMAGE", {std::string("image"), list(refs(nf, face0)), list(refs(nl, link0)), list(refs(ne, edge0)),
                         list(refs(nv, vert0))});
  put(connect, "T_CONNECT", {std::string("connect"), list(refs(nn, node0))});
  put(pointset, "T_POINTSET", {std::string("pointset"), list(refs(np, point0))});
  for (std::size_t v = 0; v < nv; ++v) {
    const TVertex& x = im.vertices[v];
    put(pos0 + v, "POINT_ON_SURFACE", {std::string(), reference(image), x.s, x.t});
    std::vector<Parameter> p{label("v", v), reference(pos0 + v)};
    for (int l : x.links) p.push_back(ref_or_unset(l, link0));
    put(vert0 + v, "T_VERTEX", std::move(p));
  }
  std::vector<int> link_face(nl, -1);
  for (std::size_t fc = 0; fc < nf; ++fc)
    for (int l : im.faces[fc].loop) link_face[static_cast<std::size_t>(l)] = static_cast<int>(fc);
  std::vector<std::array<int, 2>> edge_faces(ne, {-1, -1});  // left (forward link), right
  for (std::size_t l = 0; l < nl; ++l)
    edge_faces[static_cast<std::size_t>(im.links[l].edge)][im.links[l].sense ? 0 : 1] = link_face[l];
  for (std::size_t e = 0; e < ne; ++e) {
    const auto [left, right] = edge_faces[e];
    put(edge0 + e, "T_EDGE", {label("e", e), reference(vert0 + static_cast<std::uint64_t>(im.edges[e].start)),
                              reference(vert0 + static_cast<std::uint64_t>(im.edges[e].end)), ref_or_unset(left, face0),
                              ref_or_unset(right, face0), logical(left < 0 || right < 0)});
  }
  for (std::size_t l = 0; l < nl; ++l)
    put(link0 + l, "T_LINK", {label("l", l), Derived{}, Derived{},
                              reference(edge0 + static_cast<std::uint64_t>(im.links[l].edge)), logical(im.links[l].sense)});
  for (std::size_t c = 0; c < nc; ++c)
    put(cond0 + c, "T_EDGE_CONDITION", {label("ec", c), reference(edge0 + static_cast<std::uint64_t>(im.conditions[c].edge)),
                                        logical(im.conditions[c].flag)});
  for (std::size_t fc = 0; fc < nf; ++fc) {
    std::vector<Parameter> loop;
    for (int l : im.faces[fc].loop) loop.push_back(reference(link0 + static_cast<std::uint64_t>(l)));
    put(loop0 + fc, "EDGE_LOOP", {std::string(), list(std::move(loop))});
    put(bound0 + fc, "FACE_BOUND", {std::string(), reference(loop0 + fc), logical(true)});
    put(face0 + fc, "T_FACE", {label("f", fc), list({reference(bound0 + fc)})});
  }
  for (std::size_t n = 0; n < nn; ++n) {
    const TNode& x = ts.connect.nodes[n];
    const std::uint64_t anchor = (x.kind == TAnchorKind::vertex ? vert0 : x.kind == TAnchorKind::link ? link0 : face0) +
                                 static_cast<std::uint64_t>(x.anchor);
    std::vector<Parameter> p{label("n", n), reference(anchor), reference(point0 + static_cast<std::uint64_t>(x.point))};
    for (int m : x.neighbours) p.push_back(ref_or_unset(m, node0));
    put(node0 + n, "T_NODE_V4", std::move(p));
  }
  for (std::size_t i = 0; i < np; ++i) {
    const RationalPoint& p = ts.pointset.points[i];
    put(point0 + i, "RATIONAL_POINT", {label("p", i), list({p.xyz[0], p.xyz[1], p.xyz[2]}), p.w});
  }
  return surf;
}

std::vector<StepTSpline> read_t_spline_surfaces(const ExchangeFile& file, const std::string& name) {
  std::vector<StepTSpline> out;
  const Mapper m(file, name);
  for (const Instance& in : file.instances())
    if (in.is("T_SPLINE_SURFACE")) {
      StepTSpline t;
      t.id = in.id;
      t.entity = "T_SPLINE_SURFACE";
      TSpline ts = m.map(in);
      t.name = ts.name;
      t.degrees = ts.degrees;
      t.layers = std::move(ts);
      out.push_back(std::move(t));
    }
  return out;
}

ExchangeFile t_spline_exchange_file(const TSpline& ts, TSplineStepForm form, const std::string& name) {
  ExchangeFile f;
  if (form == TSplineStepForm::t_spline_entities) {
    f.header.description = {"T-spline surface (Xiao et al. 2016 entities)"};
    f.header.schemas = {"integrated_cnc_schema"};
    add_t_spline(f, ts, name);
    return f;
  }
  f.header.description = {"T-spline surface as an ISO 10303-42 locally refined spline surface"};
  f.header.schemas = {GeometryFileOptions{}.schema};
  const TSplineSurface surface(ts);
  const TSplineClass c = classify(ts, surface, false);
  bool rational = false;
  for (const RationalPoint& p : ts.pointset.points) rational = rational || p.w != 1.0;
  std::vector<LRBSpline<2>> basis(surface.basis().begin(), surface.basis().end());
  if (!rational)
    for (auto& b : basis) b.coef.resize(3);
  const auto ctx = add_geometric_context(f, 3);
  const auto id = add_locally_refined_surface(f, ts.degrees, basis, surface.domain(), 3, rational, c.part42_type(), name);
  f.add({"SHAPE_REPRESENTATION", {std::string("trivar"), list({reference(id)}), reference(ctx)}});
  return f;
}

void write_t_spline_step(const std::string& path, const TSpline& ts, TSplineStepForm form, const std::string& time_stamp) {
  ExchangeFile f = t_spline_exchange_file(ts, form, ts.name);
  f.header.name = path.substr(path.find_last_of('/') + 1);
  WriteOptions w;
  w.time_stamp = time_stamp;
  w.renumber = false;
  write_exchange_file(path, f, w);
}

}  // namespace trivar::io::step
