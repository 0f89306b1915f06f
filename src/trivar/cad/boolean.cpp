#include "trivar/cad/boolean.hpp"

#include <BRepAlgoAPI_BuilderAlgo.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <TopoDS_Compound.hxx>
#include <Poly_Triangulation.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "trivar/cad/brep_mapping.hpp"
#include "trivar/core/error.hpp"
#include "trivar/model/attribute_blend.hpp"
#include "trivar/model/expression.hpp"
#include "trivar/model/triangle_mesh.hpp"
#include "trivar/spline/point_inversion.hpp"

namespace trivar::cad {

BooleanOp boolean_op(const std::string& name) {
  if (name == "union") return BooleanOp::unite;
  if (name == "difference") return BooleanOp::subtract;
  if (name == "intersection") return BooleanOp::intersect;
  throw Error("Boolean: unknown operation '" + name + "' (expected union, difference or intersection)");
}

BlendRule blend_rule(const std::string& name) {
  if (name == "a") return BlendRule::take_a;
  if (name == "b") return BlendRule::take_b;
  if (name == "average") return BlendRule::average;
  if (name == "formula") return BlendRule::formula;
  if (name == "distance") return BlendRule::distance;
  throw Error("Boolean: unknown attribute rule '" + name + "' (expected a, b, average, formula or distance)");
}

namespace {

using Point = std::array<double, 3>;

// Distance from p to the triangle abc.
double triangle_distance(const Point& p, const Point& a, const Point& b, const Point& c) {
  const auto w = closest_on_triangle(p, a, b, c);
  double s = 0;
  for (int k = 0; k < 3; ++k) {
    const double d = p[k] - (w[0] * a[k] + w[1] * b[k] + w[2] * c[k]);
    s += d * d;
  }
  return std::sqrt(s);
}

// A set of triangles and the distance of points to it (boxes first, so far triangles cost one box test).
class TriangleSet {
public:
  void add(const Point& a, const Point& b, const Point& c) {
    tris_.push_back({a, b, c});
    Box<3> box = Box<3>::empty();
    for (const Point& x : {a, b, c}) box.extend(x.data());
    boxes_.push_back(box);
  }
  bool empty() const { return tris_.empty(); }
  double distance(const Point& p) const {
    double best = INFINITY;
    for (std::size_t t = 0; t < tris_.size(); ++t) {
      double lb = 0;
      for (int k = 0; k < 3; ++k) {
        const double g = std::max({boxes_[t].lo[k] - p[k], 0.0, p[k] - boxes_[t].hi[k]});
        lb += g * g;
      }
      if (lb >= best * best) continue;
      best = std::min(best, triangle_distance(p, tris_[t][0], tris_[t][1], tris_[t][2]));
    }
    return best;
  }

private:
  std::vector<std::array<Point, 3>> tris_;
  std::vector<Box<3>> boxes_;
};

// An operand cell's attributes at model points: a trimmed cell's parameters are model coordinates, others
// invert their trivariate.
class CellSampler {
public:
  explicit CellSampler(const VCell& cell) : cell_(cell) {
    if (!cell.is_trimmed()) inverter_ = std::make_unique<PointInverter<3>>(cell.geometry());
  }
  const VCell& cell() const { return cell_; }
  void eval(const Attribute& a, const Point& x, double* out) const {
    Param<3> u = x;
    if (inverter_) {
      const Box<3> dom = cell_.geometry().domain();
      InversionResult<3> r = inverter_->invert(x.data(), dom.center());
      // Outside the cell (the corners of a fitted field's box) the nearest parameter Newton reached extends the
      // attribute; inside it the inversion converges.
      u = r.param;
      for (int k = 0; k < 3; ++k) u[k] = std::clamp(u[k], dom.lo[k], dom.hi[k]);
    }
    a.eval(cell_.geometry(), u, out);
  }

private:
  const VCell& cell_;
  std::unique_ptr<PointInverter<3>> inverter_;
};

// An attribute a result cell takes over unchanged: constants, model-space formulas, and parametric formulas of
// trimmed cells (whose parameters are model coordinates, as the result cell's are).
bool carries_exactly(const VCell& from, const Attribute& a) {
  return a.kind() == Attribute::Kind::constant ||
         (a.kind() == Attribute::Kind::expression && (a.space() == Attribute::Space::model || from.is_trimmed()));
}

// The attribute's components as model-space formula texts, when it has them.
std::optional<std::vector<std::string>> formula_texts(const Attribute& a) {
  std::vector<std::string> t;
  if (a.kind() == Attribute::Kind::constant) {
    for (double v : a.values()) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.17g", v);
      t.push_back(std::string("(") + buf + ")");
    }
    return t;
  }
  if (a.kind() == Attribute::Kind::expression && a.space() == Attribute::Space::model) {
    for (const Expression& e : a.expressions()) t.push_back("(" + e.text() + ")");
    return t;
  }
  return std::nullopt;
}

struct Piece {
  int a = -1, b = -1;  // operand cells containing it
  bool kept = false;
  int cell = -1;       // result cell
};

}  // namespace

VModel boolean(const VModel& a, const VModel& b, BooleanOp op, const BooleanOptions& options, BooleanReport* report) {
  require(a.num_cells() > 0 && b.num_cells() > 0, "Boolean: an operand has no cells");
  std::map<std::string, Expression> weights;
  const auto check_rule = [&](const std::string& name, const AttributeRule& r) {
    if (r.rule != BlendRule::formula) return;
    require(!r.weight.empty(), "Boolean: attribute rule '" + name + "': the formula rule needs a weight formula in x, y, z");
    weights[r.weight] = Expression::parse(r.weight, {"x", "y", "z"});
  };
  check_rule("default", options.default_rule);
  for (const auto& [name, r] : options.rules) check_rule(name, r);
  require(options.fuzzy >= 0 && options.chordal_tolerance >= 0 && options.angular_tolerance > 0,
          "Boolean: tolerances must be >= 0 (the angular tolerance > 0)");

  Box<3> all = a.bounding_box();
  {
    const Box<3> bb = b.bounding_box();
    all.extend(bb.lo.data());
    all.extend(bb.hi.data());
  }
  const double diag = all.diagonal();
  const double chordal = options.chordal_tolerance > 0 ? options.chordal_tolerance : 1e-3 * diag;
  BooleanReport rep;
  rep.cells_a = a.num_cells();
  rep.cells_b = b.num_cells();

  const VModel* operands[2] = {&a, &b};
  std::vector<TopoDS_Solid> args;  // A's cells, then B's
  bool shared[2] = {false, false};
  for (int s = 0; s < 2; ++s) {
    OperandSolids os = operand_solids(*operands[s], s == 0 ? "A" : "B");
    shared[s] = os.shared_faces;
    for (TopoDS_Solid& solid : os.solids) args.push_back(std::move(solid));
  }

  VModel out;
  try {
    BRepAlgoAPI_BuilderAlgo gf;
    // An operand whose cells share their faces is one argument: its cells are not intersected with one another.
    // Otherwise (an earlier Boolean's result) its cells have coincident faces only, which the kernel identifies
    // when they are arguments of their own.
    TopTools_ListOfShape list;
    for (int s = 0, first = 0; s < 2; first += operands[s]->num_cells(), ++s) {
      if (!shared[s]) {
        for (int c = 0; c < operands[s]->num_cells(); ++c) list.Append(args[static_cast<std::size_t>(first + c)]);
        continue;
      }
      BRep_Builder bb;
      TopoDS_Compound compound;
      bb.MakeCompound(compound);
      for (int c = 0; c < operands[s]->num_cells(); ++c) bb.Add(compound, args[static_cast<std::size_t>(first + c)]);
      list.Append(compound);
    }
    gf.SetArguments(list);
    gf.SetFuzzyValue(options.fuzzy * diag);
    gf.SetNonDestructive(true);
    gf.Build();
    require(gf.IsDone() && !gf.HasErrors(), "Boolean: the geometry kernel's general fuse of the operands' cells failed");
    const TopoDS_Shape& fused = gf.Shape();

    // Pieces and the operand cells containing them.
    TopTools_IndexedMapOfShape solids;
    TopExp::MapShapes(fused, TopAbs_SOLID, solids);
    std::vector<Piece> pieces(static_cast<std::size_t>(solids.Extent()));
    for (std::size_t i = 0; i < args.size(); ++i) {
      const bool in_a = static_cast<int>(i) < a.num_cells();
      const int cell = in_a ? static_cast<int>(i) : static_cast<int>(i) - a.num_cells();
      TopTools_ListOfShape images = gf.Modified(args[i]);
      if (images.IsEmpty() && !gf.IsDeleted(args[i])) images.Append(args[i]);
      for (const TopoDS_Shape& im : images) {
        const int p = solids.FindIndex(im) - 1;
        if (p < 0) continue;
        int& owner = in_a ? pieces[static_cast<std::size_t>(p)].a : pieces[static_cast<std::size_t>(p)].b;
        require(owner < 0, std::string("Boolean: cells ") + std::to_string(owner) + " and " + std::to_string(cell) + " of " +
                               (in_a ? "A" : "B") + " overlap (the cells of an operand may share faces only)");
        owner = cell;
      }
    }
    for (std::size_t p = 0; p < pieces.size(); ++p)
      require(pieces[p].a >= 0 || pieces[p].b >= 0,
              "Boolean: the geometry kernel's fuse returned piece " + std::to_string(p) + ", which no cell contains");
    rep.pieces = static_cast<int>(pieces.size());
    for (Piece& p : pieces) {
      const bool ia = p.a >= 0, ib = p.b >= 0;
      rep.pieces_a_only += ia && !ib;
      rep.pieces_b_only += ib && !ia;
      rep.pieces_both += ia && ib;
      p.kept = op == BooleanOp::unite ? (ia || ib) : op == BooleanOp::subtract ? (ia && !ib) : op == BooleanOp::split ? ia : (ia && ib);
    }
    require(std::any_of(pieces.begin(), pieces.end(), [](const Piece& p) { return p.kept; }),
            std::string("Boolean: the ") + (op == BooleanOp::subtract ? "difference" : "intersection") +
                " is empty (a V-model needs at least one cell)");

    // One triangulation of every face, shared by the pieces on either side.
    // The pieces' faces lie on the operands' faces, which are B-spline surfaces already (the cells' faces were
    // given to the kernel as such), so no NURBS conversion is needed; the mapping converts the edge curves.
    const TopoDS_Shape& nurbs = fused;
    BRepMesh_IncrementalMesh mesh(nurbs, chordal, false, options.angular_tolerance, true);
    std::vector<TopoDS_Shape> converted(pieces.size());
    for (std::size_t p = 0; p < pieces.size(); ++p) converted[p] = solids(static_cast<int>(p) + 1);
    TopTools_IndexedDataMapOfShapeListOfShape face_solids;
    TopExp::MapShapesAndAncestors(nurbs, TopAbs_FACE, TopAbs_SOLID, face_solids);
    TopTools_IndexedMapOfShape piece_index;
    for (const TopoDS_Shape& s : converted) piece_index.Add(s);
    // The pieces on either side of a face (-1: outside every operand).
    const auto sides = [&](const TopoDS_Shape& face) {
      std::array<int, 2> s{-1, -1};
      int n = 0;
      for (const TopoDS_Shape& sol : face_solids.FindFromKey(face))
        if (const int i = piece_index.FindIndex(sol) - 1; i >= 0 && n < 2 && (n == 0 || s[0] != i)) s[n++] = i;
      return s;
    };

    // The parts of each operand's boundary inside the other, for distance blends: faces of overlap pieces whose
    // other side is outside that operand.
    TriangleSet inside_a, inside_b;  // (boundary of A inside B), (boundary of B inside A)
    const auto add_face_triangles = [](TriangleSet& set, const TopoDS_Face& face) {
      TopLoc_Location loc;
      const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, loc);
      if (tri.IsNull()) return;
      for (int t = 1; t <= tri->NbTriangles(); ++t) {
        int n[3];
        tri->Triangle(t).Get(n[0], n[1], n[2]);
        Point x[3];
        for (int k = 0; k < 3; ++k) {
          const gp_Pnt q = tri->Node(n[k]).Transformed(loc.Transformation());
          x[k] = {q.X(), q.Y(), q.Z()};
        }
        set.add(x[0], x[1], x[2]);
      }
    };
    for (int f = 1; f <= face_solids.Extent(); ++f) {
      const auto s = sides(face_solids.FindKey(f));
      for (int k = 0; k < 2; ++k) {
        if (s[k] < 0) continue;
        const Piece& p = pieces[static_cast<std::size_t>(s[k])];
        if (p.a < 0 || p.b < 0) continue;
        const int other = s[1 - k];
        const bool other_in_a = other >= 0 && pieces[static_cast<std::size_t>(other)].a >= 0;
        const bool other_in_b = other >= 0 && pieces[static_cast<std::size_t>(other)].b >= 0;
        const TopoDS_Face& face = TopoDS::Face(face_solids.FindKey(f));
        if (!other_in_a) add_face_triangles(inside_a, face);
        if (!other_in_b) add_face_triangles(inside_b, face);
      }
    }

    std::vector<std::unique_ptr<CellSampler>> samplers[2];
    for (int s = 0; s < 2; ++s)
      for (int c = 0; c < operands[s]->num_cells(); ++c)
        samplers[s].push_back(std::make_unique<CellSampler>(operands[s]->cell(c)));
    out.set_materials(!a.materials().empty() ? a.materials() : b.materials());

    for (std::size_t pi = 0; pi < pieces.size(); ++pi) {
      Piece& p = pieces[pi];
      if (!p.kept) continue;
      const std::string what = "Boolean: piece " + std::to_string(pi) + " (" +
                               (p.a >= 0 ? "A cell " + std::to_string(p.a) : std::string()) +
                               (p.a >= 0 && p.b >= 0 ? ", " : "") +
                               (p.b >= 0 ? "B cell " + std::to_string(p.b) : std::string()) + ")";
      SolidMapper mapper(converted[pi], chordal);
      int fi = 0;
      for (TopExp_Explorer f(converted[pi], TopAbs_FACE); f.More(); f.Next(), ++fi) {
        const auto s = sides(f.Current());
        const std::string name = "piece " + std::to_string(pi) + " face " + std::to_string(fi) +
                                 (s[1] >= 0 ? " (shared with piece " + std::to_string(s[0] == static_cast<int>(pi) ? s[1] : s[0]) + ")" : "");
        if (std::string why = mapper.add_face(TopoDS::Face(f.Current()), "bspline", name); !why.empty())
          throw Error(what + ": " + name + ": " + why);
      }
      std::shared_ptr<const TrimmedSolid> trim;
      try {
        trim = std::make_shared<const TrimmedSolid>(mapper.take());
      } catch (const Error& e) {
        throw Error(what + ": " + e.what());
      }
      const Box<3> box = trim->bounding_box();
      VCell cell(identity_box(box), trim);

      // Attributes: every name either operand cell carries.
      const VCell* ca = p.a >= 0 ? &a.cell(p.a) : nullptr;
      const VCell* cb = p.b >= 0 ? &b.cell(p.b) : nullptr;
      std::map<std::string, int> names;
      if (ca)
        for (const auto& kv : ca->attributes()) names[kv.first] |= 1;
      if (cb && op != BooleanOp::split)
        for (const auto& kv : cb->attributes()) names[kv.first] |= 2;
      for (const auto& [name, which] : names) {
        const auto rit = options.rules.find(name);
        const AttributeRule& rule = rit != options.rules.end() ? rit->second : options.default_rule;
        // One side only: that side's attribute.
        int side = which == 1 ? 0 : which == 2 ? 1 : -1;
        if (side < 0 && rule.rule == BlendRule::take_a) side = 0;
        if (side < 0 && rule.rule == BlendRule::take_b) side = 1;
        if (side >= 0) {
          const VCell& from = side == 0 ? *ca : *cb;
          const Attribute& attr = from.attribute(name);
          if (carries_exactly(from, attr)) {
            cell.set_attribute(name, attr);
            ++rep.exact_attributes;
          } else {
            const CellSampler& smp = *samplers[side][static_cast<std::size_t>(side == 0 ? p.a : p.b)];
            cell.set_attribute(name, fit_attribute(box, attr.components(), options.field,
                                                   [&](const Point& x, double* v) { smp.eval(attr, x, v); }));
            ++rep.fitted_attributes;
          }
          continue;
        }
        const Attribute& aa = ca->attribute(name);
        const Attribute& ab = cb->attribute(name);
        require(aa.components() == ab.components(), [&] {
          return "Boolean: attribute '" + name + "' has " + std::to_string(aa.components()) + " components in A cell " +
                 std::to_string(p.a) + " but " + std::to_string(ab.components()) + " in B cell " + std::to_string(p.b) +
                 " (cannot blend them)";
        });
        const int nc = aa.components();
        // Closed forms: constants and model-space formulas combine into formulas.
        const auto ta = formula_texts(aa), tb = formula_texts(ab);
        if (rule.rule != BlendRule::distance && ta && tb) {
          if (rule.rule == BlendRule::average && aa.kind() == Attribute::Kind::constant && ab.kind() == Attribute::Kind::constant) {
            std::vector<double> v(static_cast<std::size_t>(nc));
            for (int k = 0; k < nc; ++k) v[k] = 0.5 * (aa.values()[k] + ab.values()[k]);
            cell.set_attribute(name, Attribute::constant(std::move(v)));
          } else {
            std::vector<std::string> comps;
            for (int k = 0; k < nc; ++k)
              comps.push_back(rule.rule == BlendRule::average
                                  ? "0.5*" + (*ta)[k] + " + 0.5*" + (*tb)[k]
                                  : "(1 - (" + rule.weight + "))*" + (*ta)[k] + " + (" + rule.weight + ")*" + (*tb)[k]);
            cell.set_attribute(name, Attribute::expression(comps, Attribute::Space::model));
          }
          ++rep.exact_attributes;
          continue;
        }
        const CellSampler& sa = *samplers[0][static_cast<std::size_t>(p.a)];
        const CellSampler& sb = *samplers[1][static_cast<std::size_t>(p.b)];
        const Expression* w = rule.rule == BlendRule::formula ? &weights.at(rule.weight) : nullptr;
        cell.set_attribute(name, fit_attribute(box, nc, options.field, [&](const Point& x, double* v) {
          std::vector<double> va(static_cast<std::size_t>(nc)), vb(static_cast<std::size_t>(nc));
          sa.eval(aa, x, va.data());
          sb.eval(ab, x, vb.data());
          double wb = 0.5;
          if (w) wb = w->eval(x);
          if (rule.rule == BlendRule::distance) {
            const double da = inside_a.empty() ? 0 : inside_a.distance(x), db = inside_b.empty() ? 0 : inside_b.distance(x);
            blend_union(va, vb, true, true, da, db, {v, static_cast<std::size_t>(nc)});
            return;
          }
          for (int k = 0; k < nc; ++k) v[k] = (1 - wb) * va[static_cast<std::size_t>(k)] + wb * vb[static_cast<std::size_t>(k)];
        }));
        ++rep.fitted_attributes;
      }
      p.cell = out.add_cell(std::move(cell));
    }

    // Neighbours across the faces two kept pieces share.
    rep.neighbours.assign(static_cast<std::size_t>(out.num_cells()), {});
    for (int f = 1; f <= face_solids.Extent(); ++f) {
      const auto s = sides(face_solids.FindKey(f));
      const bool k0 = s[0] >= 0 && pieces[static_cast<std::size_t>(s[0])].kept;
      const bool k1 = s[1] >= 0 && pieces[static_cast<std::size_t>(s[1])].kept;
      if (k0 && k1) {
        ++rep.interior_faces;
        const int c0 = pieces[static_cast<std::size_t>(s[0])].cell, c1 = pieces[static_cast<std::size_t>(s[1])].cell;
        rep.neighbours[static_cast<std::size_t>(c0)].push_back(c1);
        rep.neighbours[static_cast<std::size_t>(c1)].push_back(c0);
      } else if (k0 || k1) {
        ++rep.boundary_faces;
      }
    }
    for (auto& n : rep.neighbours) {
      std::sort(n.begin(), n.end());
      n.erase(std::unique(n.begin(), n.end()), n.end());
    }
  } catch (const Standard_Failure& e) {
    throw Error("Boolean: the geometry kernel failed: " + std::string(e.GetMessageString()));
  }
  rep.cells = out.num_cells();
  out.glue();
  if (report) *report = std::move(rep);
  return out;
}

}  // namespace trivar::cad
