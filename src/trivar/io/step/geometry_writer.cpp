#include "trivar/io/step/geometry_writer.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <map>
#include <tuple>

#include "trivar/core/error.hpp"
#include "trivar/io/step/bspline_entity_names.hpp"

namespace trivar::io::step {

namespace {

Parameter unknown() { return enumeration("U"); }

void check_dim(int dim) {
  require(dim >= 1 && dim <= 3, "STEP: control dimension " + std::to_string(dim) +
                                    " cannot be written (CARTESIAN_POINT holds 1 to 3 coordinates)");
}

std::uint64_t add_point(ExchangeFile& f, const double* x, int dim) {
  std::vector<Parameter> c;
  c.reserve(static_cast<std::size_t>(dim));
  for (int i = 0; i < dim; ++i) c.emplace_back(x[i]);
  return f.add({"CARTESIAN_POINT", {std::string(), list(std::move(c))}});
}

// Nested list (u outermost) of the values leaf(linear index) over a grid stored u fastest.
template <int D, class Leaf>
Parameter grid(const TensorSpline<D>& s, Leaf leaf) {
  const auto n = s.counts();
  std::function<Parameter(int, std::array<int, D>&)> build = [&](int k, std::array<int, D>& idx) -> Parameter {
    std::vector<Parameter> items;
    items.reserve(static_cast<std::size_t>(n[static_cast<std::size_t>(k)]));
    for (int i = 0; i < n[static_cast<std::size_t>(k)]; ++i) {
      idx[static_cast<std::size_t>(k)] = i;
      if (k + 1 == D)
        items.push_back(leaf(s.linear_index(idx)));
      else
        items.push_back(build(k + 1, idx));
    }
    return list(std::move(items));
  };
  std::array<int, D> idx{};
  return build(0, idx);
}

template <int D>
std::uint64_t add_tensor(ExchangeFile& f, const TensorSpline<D>& s, const std::string& name) {
  check_dim(s.dim());
  constexpr std::size_t d = D - 1;
  std::vector<std::uint64_t> points(static_cast<std::size_t>(s.num_coefs()));
  std::vector<double> x(static_cast<std::size_t>(s.dim()));
  for (int i = 0; i < s.num_coefs(); ++i) {
    if (s.is_rational()) {
      s.control_point(i, x.data());
    } else {
      std::copy_n(s.coef(i), s.dim(), x.begin());
    }
    points[static_cast<std::size_t>(i)] = add_point(f, x.data(), s.dim());
  }
  std::vector<Parameter> base;
  for (int k = 0; k < D; ++k) base.emplace_back(static_cast<std::int64_t>(s.degree(k)));
  base.push_back(grid<D>(s, [&](int i) { return reference(points[static_cast<std::size_t>(i)]); }));
  if (D == 1) base.insert(base.end(), {enumeration("UNSPECIFIED"), unknown(), unknown()});
  if (D == 2) base.insert(base.end(), {enumeration("UNSPECIFIED"), unknown(), unknown(), unknown()});
  std::vector<Parameter> mults, values;
  for (int k = 0; k < D; ++k) {
    std::vector<Parameter> m, v;
    for (int c : s.knots(k).multiplicities()) m.emplace_back(static_cast<std::int64_t>(c));
    for (double t : s.knots(k).unique()) v.emplace_back(t);
    mults.push_back(list(std::move(m)));
    values.push_back(list(std::move(v)));
  }
  std::vector<Parameter> knots = mults;
  knots.insert(knots.end(), values.begin(), values.end());
  if (D < 3) knots.push_back(enumeration("UNSPECIFIED"));
  if (!s.is_rational()) {
    std::vector<Parameter> params{name};
    params.insert(params.end(), base.begin(), base.end());
    params.insert(params.end(), knots.begin(), knots.end());
    return f.add({kWithKnots[d], std::move(params)});
  }
  std::vector<Record> records{{kBase[d], std::move(base)},
                              {kWithKnots[d], std::move(knots)},
                              {"GEOMETRIC_REPRESENTATION_ITEM", {}},
                              {kRational[d], {grid<D>(s, [&](int i) { return Parameter(s.weight(i)); })}},
                              {"REPRESENTATION_ITEM", {name}}};
  if (D == 1) records.insert(records.end(), {{"BOUNDED_CURVE", {}}, {"CURVE", {}}});
  if (D == 2) records.insert(records.end(), {{"BOUNDED_SURFACE", {}}, {"SURFACE", {}}});
  if (D == 3) records.push_back({"VOLUME", {}});
  return f.add_complex(std::move(records));
}

// Any collection of scaled B-splines (an LR spline, the blending functions of a T-spline) with its type.
template <int D>
std::uint64_t add_scaled(ExchangeFile& f, const Ints<D>& degrees, std::span<const LRBSpline<D>> basis,
                         const Box<D>& box, int dim, bool rational, const char* type, const std::string& name) {
  check_dim(dim);
  std::array<std::vector<double>, D> values;
  for (const auto& b : basis)
    for (std::size_t k = 0; k < D; ++k) values[k].insert(values[k].end(), b.knots[k].begin(), b.knots[k].end());
  for (auto& v : values) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  // Local B-splines are shared between the LR B-splines with the same knots in a direction.
  std::map<std::tuple<int, std::vector<std::int64_t>, std::vector<std::int64_t>>, std::uint64_t> locals;
  std::array<std::vector<Parameter>, D> refs;
  std::vector<Parameter> points, gammas, weights;
  std::vector<double> x(static_cast<std::size_t>(dim));
  for (const auto& b : basis) {
    for (std::size_t k = 0; k < D; ++k) {
      std::vector<std::int64_t> ix, m;
      const auto& t = b.knots[k];
      for (std::size_t j = 0; j < t.size();) {
        std::size_t e = j;
        while (e < t.size() && t[e] == t[j]) ++e;
        ix.push_back(std::lower_bound(values[k].begin(), values[k].end(), t[j]) - values[k].begin() + 1);
        m.push_back(static_cast<std::int64_t>(e - j));
        j = e;
      }
      auto key = std::make_tuple(degrees[k], ix, m);
      auto it = locals.find(key);
      if (it == locals.end()) {
        std::vector<Parameter> pi(ix.begin(), ix.end()), pm(m.begin(), m.end());
        const std::uint64_t id = f.add({"LOCAL_B_SPLINE", {std::string(), static_cast<std::int64_t>(degrees[k]),
                                                           list(std::move(pi)), list(std::move(pm))}});
        it = locals.emplace(std::move(key), id).first;
      }
      refs[k].push_back(reference(it->second));
    }
    const double w = rational ? b.coef[static_cast<std::size_t>(dim)] : 1.0;
    for (int c = 0; c < dim; ++c)
      x[static_cast<std::size_t>(c)] = rational ? b.coef[static_cast<std::size_t>(c)] / w : b.coef[static_cast<std::size_t>(c)];
    points.push_back(reference(add_point(f, x.data(), dim)));
    gammas.emplace_back(b.gamma);
    weights.emplace_back(w);
  }
  std::vector<Parameter> params{name};
  for (auto& r : refs) params.push_back(list(std::move(r)));
  for (const auto& v : values) params.push_back(list(std::vector<Parameter>(v.begin(), v.end())));
  params.push_back(list(std::move(points)));
  params.push_back(list(std::move(gammas)));
  params.push_back(enumeration("NOT_TESTED"));
  params.push_back(enumeration(type));
  if (D == 2) params.insert(params.end(), {unknown(), unknown(), unknown()});
  std::vector<Parameter> domain;
  for (int k = 0; k < D; ++k)
    domain.push_back(list({Parameter(box.lo[static_cast<std::size_t>(k)]), Parameter(box.hi[static_cast<std::size_t>(k)])}));
  params.push_back(list(std::move(domain)));
  if (!rational)
    return f.add({D == 2 ? "LOCALLY_REFINED_SPLINE_SURFACE" : "LOCALLY_REFINED_SPLINE_VOLUME", std::move(params)});
  params.push_back(list(std::move(weights)));
  return f.add({D == 2 ? "RATIONAL_LOCALLY_REFINED_SPLINE_SURFACE" : "RATIONAL_LOCALLY_REFINED_SPLINE_VOLUME",
                std::move(params)});
}

template <int D>
std::uint64_t add_lr(ExchangeFile& f, const LRSpline<D>& s, const std::string& name) {
  return add_scaled<D>(f, s.degrees(), s.basis_functions(), s.domain(), s.dim(), s.is_rational(), "LR_B_SPLINE", name);
}

template <int D>
std::uint64_t add_hier(ExchangeFile& f, const HierarchicalSpline<D>& s, const std::string& name) {
  const HierarchicalSpline<D> hb = s.space().basis() == HierarchicalBasis::hb ? s : s.with_basis(HierarchicalBasis::hb);
  const HierarchicalSpace<D>& space = hb.space();
  std::vector<std::array<KnotVector, D>> knots(static_cast<std::size_t>(space.num_levels()));
  for (int l = 0; l < space.num_levels(); ++l)
    for (int k = 0; k < D; ++k) knots[static_cast<std::size_t>(l)][static_cast<std::size_t>(k)] = space.hierarchy().knots(l, k);
  std::vector<LRBSpline<D>> basis(static_cast<std::size_t>(space.num_basis()));
  for (int id = 0; id < space.num_basis(); ++id) {
    const HierarchicalFunction<D> fn = space.function(id);
    LRBSpline<D>& b = basis[static_cast<std::size_t>(id)];
    for (int k = 0; k < D; ++k) {
      const KnotVector& kv = knots[static_cast<std::size_t>(fn.level)][static_cast<std::size_t>(k)];
      b.knots[k].assign(kv.data() + fn.index[k], kv.data() + fn.index[k] + space.degree(k) + 2);
    }
    b.gamma = 1.0;
    b.coef.assign(hb.coef(id), hb.coef(id) + hb.stride());
  }
  return add_scaled<D>(f, space.degrees(), basis, space.domain(), hb.dim(), hb.is_rational(), "HIERARCHICAL_B_SPLINE", name);
}

std::uint64_t add_si_unit(ExchangeFile& f, const char* unit_kind, Parameter prefix, const char* name) {
  return f.add_complex({{unit_kind, {}}, {"NAMED_UNIT", {Derived{}}}, {"SI_UNIT", {std::move(prefix), enumeration(name)}}});
}

}  // namespace

std::uint64_t add_spline(ExchangeFile& file, const AnySpline& spline, const std::string& name) {
  return std::visit([&](const auto& s) { return add_tensor(file, s, name); }, spline);
}

std::uint64_t add_locally_refined_surface(ExchangeFile& file, const Ints<2>& degrees, std::span<const LRBSpline<2>> basis,
                                          const Box<2>& domain, int dim, bool rational, const std::string& type,
                                          const std::string& name) {
  return add_scaled<2>(file, degrees, basis, domain, dim, rational, type.c_str(), name);
}

std::uint64_t add_lr_spline(ExchangeFile& file, const AnyLRSpline& spline, const std::string& name) {
  return std::visit([&](const auto& s) { return add_lr(file, s, name); }, spline);
}

std::uint64_t add_hierarchical_spline(ExchangeFile& file, const AnyHierarchicalSpline& spline, const std::string& name) {
  return std::visit([&](const auto& s) { return add_hier(file, s, name); }, spline);
}

std::uint64_t add_geometric_context(ExchangeFile& file, int dimension) {
  const auto mm = add_si_unit(file, "LENGTH_UNIT", enumeration("MILLI"), "METRE");
  const auto rad = add_si_unit(file, "PLANE_ANGLE_UNIT", Unset{}, "RADIAN");
  const auto sr = add_si_unit(file, "SOLID_ANGLE_UNIT", Unset{}, "STERADIAN");
  return file.add_complex(
      {{"GEOMETRIC_REPRESENTATION_CONTEXT", {static_cast<std::int64_t>(dimension)}},
       {"GLOBAL_UNIT_ASSIGNED_CONTEXT", {list({reference(mm), reference(rad), reference(sr)})}},
       {"REPRESENTATION_CONTEXT", {std::string("trivar"), std::string(std::to_string(dimension) + "D")}}});
}

ExchangeFile geometry_exchange_file(const std::vector<AnySpline>& splines, const std::vector<AnyLRSpline>& lr_splines,
                                    const GeometryFileOptions& options) {
  return geometry_exchange_file(splines, lr_splines, {}, options);
}

ExchangeFile geometry_exchange_file(const std::vector<AnySpline>& splines, const std::vector<AnyLRSpline>& lr_splines,
                                    const std::vector<AnyHierarchicalSpline>& hierarchical,
                                    const GeometryFileOptions& options) {
  require(!splines.empty() || !lr_splines.empty() || !hierarchical.empty(), "STEP: nothing to write");
  int dim = 1;
  for (const auto& s : splines) dim = std::max(dim, std::visit([](const auto& x) { return x.dim(); }, s));
  for (const auto& s : lr_splines) dim = std::max(dim, std::visit([](const auto& x) { return x.dim(); }, s));
  for (const auto& s : hierarchical) dim = std::max(dim, std::visit([](const auto& x) { return x.dim(); }, s));
  check_dim(dim);
  ExchangeFile f;
  f.header.description = {options.description};
  f.header.schemas = {options.schema};
  const auto ctx = add_geometric_context(f, dim);
  std::vector<Parameter> items;
  std::size_t n = 0;
  const auto name = [&] { return n < options.names.size() ? options.names[n++] : (++n, std::string()); };
  for (const auto& s : splines) items.push_back(reference(add_spline(f, s, name())));
  for (const auto& s : lr_splines) items.push_back(reference(add_lr_spline(f, s, name())));
  for (const auto& s : hierarchical) items.push_back(reference(add_hierarchical_spline(f, s, name())));
  f.add({"SHAPE_REPRESENTATION", {options.representation_name, list(std::move(items)), reference(ctx)}});
  return f;
}

}  // namespace trivar::io::step
