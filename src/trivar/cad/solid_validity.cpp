#include "trivar/cad/solid_validity.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepCheck_ListOfStatus.hxx>
#include <BRepCheck_Shell.hxx>
#include <BRepCheck_Solid.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box2d.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>

#include <algorithm>
#include <numeric>
#include <vector>

namespace trivar::cad {

namespace {

int loop_count(const TopoDS_Face& f) {
  int n = 0;
  for (TopoDS_Iterator it(f); it.More(); it.Next()) n += it.Value().ShapeType() == TopAbs_WIRE;
  return n;
}

bool no_error(const BRepCheck_ListOfStatus& statuses) {
  return std::all_of(statuses.cbegin(), statuses.cend(), [](BRepCheck_Status s) { return s == BRepCheck_NoError; });
}

// A crowded face's loops as stored in it (relative to the face), split into the outer loop and the others.
struct FaceLoops {
  TopoDS_Face face;  // the face, forward and unmoved: its loops are then exactly as stored
  TopoDS_Wire outer;
  std::vector<TopoDS_Wire> inner;
  bool only_loops = true;  // no edges or vertices of the face outside its loops
};

FaceLoops face_loops(const TopoDS_Face& f) {
  FaceLoops l;
  l.face = TopoDS::Face(f.Located(TopLoc_Location()).Oriented(TopAbs_FORWARD));
  l.outer = BRepTools::OuterWire(l.face);
  for (TopoDS_Iterator it(l.face, false, false); it.More(); it.Next()) {
    if (it.Value().ShapeType() != TopAbs_WIRE)
      l.only_loops = false;
    else if (!it.Value().IsSame(l.outer))
      l.inner.push_back(TopoDS::Wire(it.Value()));
  }
  return l;
}

// The face `of` (with its location and orientation) bounded by its outer loop and the given other loops only.
TopoDS_Face restricted(const TopoDS_Face& of, const FaceLoops& l, const std::vector<std::size_t>& inner) {
  TopoDS_Face g = TopoDS::Face(l.face.EmptyCopied());
  // Adding marks the loops as not free, which they already are (they belong to the face): the conversion that
  // reads the same loops beside the check sees no change.
  BRep_Builder b;
  b.Add(g, l.outer);
  for (const std::size_t i : inner) b.Add(g, l.inner[i]);
  g.Location(of.Location());
  g.Orientation(of.Orientation());
  return g;
}

// The kernel's verdict on the face, by groups of loops and by pairs of overlapping loops in different groups.
bool crowded_face_valid(const TopoDS_Face& f) {
  const FaceLoops l = face_loops(f);
  if (l.outer.IsNull() || !l.only_loops) return BRepCheck_Analyzer(f).IsValid();
  // Parameter-space boxes of the loops, widened by the edges' tolerance there (loops within tolerance of each
  // other touch for the kernel) and a relative margin for the boxes' own rounding.
  const BRepAdaptor_Surface surface(l.face, false);
  const double tol = BRep_Tool::MaxTolerance(l.face, TopAbs_EDGE);
  const double gap = 2 * std::max(surface.UResolution(tol), surface.VResolution(tol));
  struct Box {
    double u0, v0, u1, v1;
  };
  std::vector<Box> boxes;
  boxes.reserve(l.inner.size());
  for (const TopoDS_Wire& w : l.inner) {
    Bnd_Box2d b;
    BRepTools::AddUVBounds(l.face, w, b);
    if (b.IsVoid()) return BRepCheck_Analyzer(f).IsValid();
    Box x;
    b.Get(x.u0, x.v0, x.u1, x.v1);
    const double m = gap + 1e-9 * std::max({std::abs(x.u0), std::abs(x.u1), std::abs(x.v0), std::abs(x.v1), 1.0});
    boxes.push_back({x.u0 - m, x.v0 - m, x.u1 + m, x.v1 + m});
  }
  // The loops in groups of neighbours in u, each group checked with the outer loop as one face of at most
  // crowded_face_loops loops (the outer loop's edges are checked once per group, not once per loop).
  std::vector<std::size_t> order(boxes.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return boxes[a].u0 < boxes[b].u0; });
  constexpr std::size_t group_size = crowded_face_loops - 1;
  std::vector<std::size_t> group(boxes.size());
  for (std::size_t k = 0; k < order.size(); k += group_size) {
    const std::vector<std::size_t> members(order.begin() + static_cast<std::ptrdiff_t>(k),
                                           order.begin() + static_cast<std::ptrdiff_t>(std::min(k + group_size, order.size())));
    for (const std::size_t i : members) group[i] = k;
    if (!BRepCheck_Analyzer(restricted(f, l, members)).IsValid()) return false;
  }
  // Sweep in u: each loop meets the loops still open at its start; pairs in different groups whose boxes
  // overlap are checked as a face of three loops.
  std::vector<std::size_t> open;
  for (const std::size_t i : order) {
    std::erase_if(open, [&](std::size_t j) { return boxes[j].u1 < boxes[i].u0; });
    for (const std::size_t j : open)
      if (group[i] != group[j] && boxes[j].v0 <= boxes[i].v1 && boxes[i].v0 <= boxes[j].v1 &&
          !BRepCheck_Analyzer(restricted(f, l, {i, j})).IsValid())
        return false;
    open.push_back(i);
  }
  return true;
}

}  // namespace

bool is_valid_solid(const TopoDS_Shape& solid) {
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(solid, TopAbs_FACE, faces);
  BRep_Builder b;
  TopoDS_Compound ordinary;
  b.MakeCompound(ordinary);
  std::vector<TopoDS_Face> crowded;
  for (int i = 1; i <= faces.Extent(); ++i) {
    const TopoDS_Face& f = TopoDS::Face(faces(i));
    if (loop_count(f) > crowded_face_loops)
      crowded.push_back(f);
    else
      b.Add(ordinary, f);
  }
  if (crowded.empty()) return BRepCheck_Analyzer(solid).IsValid();
  if (!BRepCheck_Analyzer(ordinary).IsValid()) return false;
  for (const TopoDS_Face& f : crowded)
    if (!crowded_face_valid(f)) return false;
  // The shells closed and consistently oriented, and the solid's shells neither crossing nor enclosing each
  // other wrongly: the kernel's own shell and solid checks, which do not classify loops.
  for (TopExp_Explorer x(solid, TopAbs_SHELL); x.More(); x.Next()) {
    const Handle(BRepCheck_Shell) shell = new BRepCheck_Shell(TopoDS::Shell(x.Current()));
    if (!shell->IsMinimum()) shell->Minimum();
    if (shell->Closed(true) != BRepCheck_NoError || shell->Orientation(true) != BRepCheck_NoError || !no_error(shell->Status()))
      return false;
  }
  for (TopExp_Explorer x(solid, TopAbs_SOLID); x.More(); x.Next()) {
    const Handle(BRepCheck_Solid) s = new BRepCheck_Solid(TopoDS::Solid(x.Current()));
    if (!s->IsMinimum()) s->Minimum();
    if (!no_error(s->Status())) return false;
  }
  return true;
}

}  // namespace trivar::cad
