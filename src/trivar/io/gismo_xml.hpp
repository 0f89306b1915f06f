#pragma once
// G+Smo XML files (`<xml>` with `<Geometry>` children, https://gismo.github.io file format): tensor B-spline and
// NURBS surfaces and volumes (TensorBSpline2/3, TensorNurbs2/3) and hierarchical splines (THBSpline2/3,
// HBSpline2/3), several per file (a multipatch: the `<MultiPatch>` node lists the geometries, which are read
// as the file's geometries in order). Parsed with libxml2.
//
// Conventions of the format, as trivar maps them: a tensor basis is one `<Basis type="BSplineBasis"
// index="k">` with a `<KnotVector degree="p">` per direction; `<coefs geoDim="g">` lists one row of g values per
// basis function, u fastest (trivar's order); NURBS give Cartesian coefficients and a `<weights>` list (trivar
// stores w*x, ..., w). A hierarchical basis holds its level-0 tensor basis (or, with manualLevels="true", one
// tensor basis per level, attribute level="l") and `<box level="l">` nodes with 2D cell indices of level l
// (lower corner, then upper corner, exclusive): the box lies in Omega^l. Functions are numbered by level, then
// u fastest inside a level, as in trivar.
//
// Hierarchies follow G+Smo's box semantics: Omega^l is the union of the boxes of level >= l, each given in
// cells of its level, so a domain may cut cells of coarser levels. The writer lists, per level, the domain
// cells no finer domain covers (what G+Smo writes: the leaves of its box tree).
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "trivar/hier/hierarchical_spline.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar::io {

using GismoGeometry = std::variant<TensorSpline<2>, TensorSpline<3>, HierarchicalSpline<2>, HierarchicalSpline<3>>;

// Every geometry of the file, in document order. Throws trivar::Error with one line naming the file, the line
// and what is wrong: malformed XML, no geometry, an unsupported type, missing nodes or attributes, bad numbers,
// sizes that disagree (coefficients, weights, knots), invalid knot vectors, boxes outside the hierarchy.
std::vector<GismoGeometry> read_gismo_xml(const std::string& path);
std::vector<GismoGeometry> parse_gismo_xml(std::string_view text, const std::string& name);

// The file text (a `<MultiPatch>` node is added for more than one geometry); written atomically.
std::string gismo_xml_text(const std::vector<GismoGeometry>& geometries);
void write_gismo_xml(const std::string& path, const std::vector<GismoGeometry>& geometries);

}  // namespace trivar::io
