#include "trivar/io/gismo_xml.hpp"

#include <libxml/parser.h>
#include <libxml/tree.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"

namespace trivar::io {

namespace {

// Most cells the boxes of one hierarchical basis may cover (each becomes a set entry while reading).
constexpr double kMaxBoxCells = 2e7;

struct Reader {
  std::string name;

  [[noreturn]] void fail(const xmlNode* n, const std::string& what) const {
    throw Error("gismo xml: " + name + (n ? ", line " + std::to_string(xmlGetLineNo(n)) : std::string()) + ": " + what);
  }
  static std::string attr(const xmlNode* n, const char* key) {
    xmlChar* v = xmlGetProp(n, reinterpret_cast<const xmlChar*>(key));
    if (!v) return {};
    std::string s(reinterpret_cast<const char*>(v));
    xmlFree(v);
    return s;
  }
  std::string need_attr(const xmlNode* n, const char* key) const {
    std::string v = attr(n, key);
    if (v.empty()) fail(n, std::string("<") + reinterpret_cast<const char*>(n->name) + "> lacks the attribute " + key);
    return v;
  }
  int int_attr(const xmlNode* n, const char* key) const {
    const std::string v = need_attr(n, key);
    char* end = nullptr;
    errno = 0;
    const long x = std::strtol(v.c_str(), &end, 10);
    if (*end || errno || x < 0 || x > 1000000000) fail(n, std::string("attribute ") + key + "=\"" + v + "\" is not a valid count");
    return static_cast<int>(x);
  }
  static bool is(const xmlNode* n, const char* tag) {
    return n->type == XML_ELEMENT_NODE && std::strcmp(reinterpret_cast<const char*>(n->name), tag) == 0;
  }
  static std::vector<const xmlNode*> children(const xmlNode* n, const char* tag) {
    std::vector<const xmlNode*> out;
    for (const xmlNode* c = n->children; c; c = c->next)
      if (is(c, tag)) out.push_back(c);
    return out;
  }
  const xmlNode* child(const xmlNode* n, const char* tag) const {
    const auto c = children(n, tag);
    if (c.empty()) fail(n, std::string("<") + reinterpret_cast<const char*>(n->name) + "> has no <" + tag + "> node");
    return c.front();
  }
  std::vector<double> numbers(const xmlNode* n) const {
    xmlChar* text = xmlNodeGetContent(n);
    std::string s = text ? reinterpret_cast<const char*>(text) : "";
    xmlFree(text);
    std::vector<double> out;
    const char* p = s.c_str();
    while (true) {
      while (*p == ' ' || *p == '\n' || *p == '\t' || *p == '\r') ++p;
      if (!*p) break;
      char* end = nullptr;
      const double x = std::strtod(p, &end);
      if (end == p || !std::isfinite(x)) {
        std::string word(p, std::strcspn(p, " \n\t\r"));
        fail(n, "'" + word + "' is not a number");
      }
      out.push_back(x);
      p = end;
    }
    return out;
  }

  // A TensorBSplineBasis<D> node: one knot vector per direction.
  template <int D>
  std::array<KnotVector, D> tensor_basis(const xmlNode* n) const {
    const std::string type = need_attr(n, "type");
    if (type != "TensorBSplineBasis" + std::to_string(D))
      fail(n, "expected a TensorBSplineBasis" + std::to_string(D) + " basis, found '" + type + "'");
    const auto parts = children(n, "Basis");
    if (static_cast<int>(parts.size()) != D)
      fail(n, "a TensorBSplineBasis" + std::to_string(D) + " needs " + std::to_string(D) + " BSplineBasis nodes, found " +
                  std::to_string(parts.size()));
    std::array<KnotVector, D> kv;
    std::array<bool, D> seen{};
    for (std::size_t i = 0; i < parts.size(); ++i) {
      const xmlNode* b = parts[i];
      if (need_attr(b, "type") != "BSplineBasis") fail(b, "expected a BSplineBasis, found '" + attr(b, "type") + "'");
      const int k = attr(b, "index").empty() ? static_cast<int>(i) : int_attr(b, "index");
      if (k >= D || seen[static_cast<std::size_t>(k)]) fail(b, "BSplineBasis index " + std::to_string(k) + " is repeated or out of range");
      seen[static_cast<std::size_t>(k)] = true;
      const xmlNode* knots = child(b, "KnotVector");
      try {
        kv[static_cast<std::size_t>(k)] = KnotVector(int_attr(knots, "degree"), numbers(knots));
      } catch (const Error& e) {
        fail(knots, e.what());
      }
    }
    return kv;
  }

  std::vector<double> coefs(const xmlNode* g, int count, int& dim) const {
    const xmlNode* c = child(g, "coefs");
    dim = int_attr(c, "geoDim");
    if (dim < 1) fail(c, "geoDim must be at least 1");
    if (!attr(c, "format").empty() && attr(c, "format") != "ascii" && attr(c, "format") != "ASCII")
      fail(c, "coefficient format '" + attr(c, "format") + "' is not supported (ascii only)");
    std::vector<double> v = numbers(c);
    if (v.size() != static_cast<std::size_t>(count) * dim)
      fail(c, std::to_string(v.size()) + " coefficient values, expected " + std::to_string(count) + " functions x geoDim " +
                  std::to_string(dim));
    if (attr(c, "order") == "coordinates") {  // all x, then all y, ...
      std::vector<double> t(v.size());
      for (int i = 0; i < count; ++i)
        for (int d = 0; d < dim; ++d) t[static_cast<std::size_t>(i) * dim + d] = v[static_cast<std::size_t>(d) * count + i];
      v.swap(t);
    }
    return v;
  }

  template <int D>
  TensorSpline<D> tensor(const xmlNode* g, bool rational) const {
    const xmlNode* basis = child(g, "Basis");
    const xmlNode* tensor_node = basis;
    std::vector<double> weights;
    if (rational) {
      if (need_attr(basis, "type") != "TensorNurbsBasis" + std::to_string(D))
        fail(basis, "expected a TensorNurbsBasis" + std::to_string(D) + " basis, found '" + attr(basis, "type") + "'");
      tensor_node = child(basis, "Basis");
      weights = numbers(child(basis, "weights"));
    }
    const auto kv = tensor_basis<D>(tensor_node);
    int n = 1;
    for (const auto& k : kv) n *= k.size();
    int dim = 0;
    const std::vector<double> c = coefs(g, n, dim);
    if (rational && weights.size() != static_cast<std::size_t>(n))
      fail(child(basis, "weights"), std::to_string(weights.size()) + " weights for " + std::to_string(n) + " functions");
    try {
      return TensorSpline<D>::from_cartesian(kv, dim, c, weights);
    } catch (const Error& e) {
      fail(g, e.what());
    }
  }

  template <int D>
  HierarchicalSpline<D> hierarchical(const xmlNode* g, HierarchicalBasis kind) const {
    const xmlNode* basis = child(g, "Basis");
    const std::string want = std::string(kind == HierarchicalBasis::thb ? "THB" : "HB") + "SplineBasis" + std::to_string(D);
    if (need_attr(basis, "type") != want) fail(basis, "expected a " + want + " basis, found '" + attr(basis, "type") + "'");
    const auto tensors = children(basis, "Basis");
    if (tensors.empty()) fail(basis, "the hierarchical basis has no tensor basis");
    std::vector<std::array<KnotVector, D>> levels;
    if (attr(basis, "manualLevels") == "true") {
      std::map<int, const xmlNode*> by_level;
      for (const xmlNode* t : tensors) by_level[int_attr(t, "level")] = t;
      for (const auto& [l, t] : by_level) {
        if (l != static_cast<int>(levels.size())) fail(t, "tensor basis of level " + std::to_string(l) + " without the levels below");
        levels.push_back(tensor_basis<D>(t));
      }
    } else {
      levels.push_back(tensor_basis<D>(tensors.front()));
    }
    std::unique_ptr<TensorHierarchy<D>> h;
    try {
      h = std::make_unique<TensorHierarchy<D>>(levels);
    } catch (const Error& e) {
      fail(basis, e.what());
    }
    // Omega^j (j >= 1) as cells of level j: the union of the boxes of level >= j.
    struct Box_ {
      const xmlNode* node;
      int level;
      Ints<D> lo, hi;
    };
    std::vector<Box_> boxes;
    int top = 0;
    for (const xmlNode* b : children(basis, "box")) {
      Box_ box{b, int_attr(b, "level"), {}, {}};
      const std::vector<double> v = numbers(b);
      if (v.size() != 2 * D) fail(b, "a box needs " + std::to_string(2 * D) + " indices, found " + std::to_string(v.size()));
      if (box.level > 40) fail(b, "box level " + std::to_string(box.level) + " is too deep");
      for (double x : v)
        if (!(x >= 0 && x <= 1e9)) fail(b, "box indices must be integers in [0, 1e9]");
      for (int k = 0; k < D; ++k) {
        box.lo[k] = static_cast<int>(v[static_cast<std::size_t>(k)]);
        box.hi[k] = static_cast<int>(v[static_cast<std::size_t>(D + k)]);
        if (v[static_cast<std::size_t>(k)] != box.lo[k] || v[static_cast<std::size_t>(D + k)] != box.hi[k] || box.lo[k] < 0 || box.hi[k] < box.lo[k])
          fail(b, "box indices must be integers with lower <= upper");
      }
      top = std::max(top, box.level);
      boxes.push_back(box);
    }
    try {
      h->ensure_levels(top + 1);
    } catch (const Error& e) {
      fail(basis, e.what());
    }
    // G+Smo's Omega^j is the union of the boxes of level >= j, each box in cells of its level (any cells of
    // the level's mesh); a box of level 0 adds nothing.
    std::vector<std::vector<Ints<D>>> cells(static_cast<std::size_t>(top) + 1);
    double total_cells = 0;
    for (const Box_& b : boxes) {
      for (int k = 0; k < D; ++k)
        if (b.hi[k] > h->axis(b.level, k).num_cells())
          fail(b.node, "box exceeds the " + std::to_string(h->axis(b.level, k).num_cells()) + " cells of level " +
                           std::to_string(b.level) + " in direction " + std::to_string(k));
      double count = 1;
      for (int k = 0; k < D; ++k) count *= b.hi[k] - b.lo[k];
      if (count == 0 || b.level == 0) continue;
      total_cells += count;
      // The cells of every box are listed: refuse absurd sizes before allocating them.
      if (total_cells > kMaxBoxCells)
        fail(b.node, "the boxes cover more than " + std::to_string(static_cast<long>(kMaxBoxCells)) + " cells");
      Ints<D> c = b.lo;
      while (true) {
        cells[static_cast<std::size_t>(b.level)].push_back(c);
        int k = 0;
        while (k < D && ++c[k] == b.hi[k]) c[k] = b.lo[k], ++k;
        if (k == D) break;
      }
    }
    HierarchicalSpace<D> space(*h, kind);
    try {
      space.extend_domains(cells);
    } catch (const Error& e) {
      fail(basis, e.what());
    }
    int dim = 0;
    std::vector<double> c = coefs(g, space.num_basis(), dim);
    try {
      return HierarchicalSpline<D>(std::move(space), dim, false, std::move(c));
    } catch (const Error& e) {
      fail(g, e.what());
    }
  }

  GismoGeometry geometry(const xmlNode* g) const {
    const std::string type = need_attr(g, "type");
    if (type == "TensorBSpline2") return tensor<2>(g, false);
    if (type == "TensorBSpline3") return tensor<3>(g, false);
    if (type == "TensorNurbs2") return tensor<2>(g, true);
    if (type == "TensorNurbs3") return tensor<3>(g, true);
    if (type == "THBSpline2") return hierarchical<2>(g, HierarchicalBasis::thb);
    if (type == "THBSpline3") return hierarchical<3>(g, HierarchicalBasis::thb);
    if (type == "HBSpline2") return hierarchical<2>(g, HierarchicalBasis::hb);
    if (type == "HBSpline3") return hierarchical<3>(g, HierarchicalBasis::hb);
    fail(g, "unsupported geometry type '" + type +
                "' (supported: TensorBSpline2/3, TensorNurbs2/3, THBSpline2/3, HBSpline2/3)");
  }
};

struct DocDeleter {
  void operator()(xmlDoc* d) const { xmlFreeDoc(d); }
};

// Full-precision numbers.
std::string num(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

template <int D>
void put_tensor_basis(std::ostream& os, const std::array<KnotVector, D>& kv, const std::string& indent) {
  os << indent << "<Basis type=\"TensorBSplineBasis" << D << "\">\n";
  for (int k = 0; k < D; ++k) {
    os << indent << " <Basis type=\"BSplineBasis\" index=\"" << k << "\">\n" << indent << "  <KnotVector degree=\""
       << kv[static_cast<std::size_t>(k)].degree() << "\">";
    for (double t : kv[static_cast<std::size_t>(k)].knots()) os << num(t) << ' ';
    os << "</KnotVector>\n" << indent << " </Basis>\n";
  }
  os << indent << "</Basis>\n";
}

void put_coefs(std::ostream& os, const double* c, int n, int dim, int stride) {
  os << "  <coefs geoDim=\"" << dim << "\">\n";
  for (int i = 0; i < n; ++i) {
    const double w = stride > dim ? c[static_cast<std::ptrdiff_t>(i) * stride + dim] : 1.0;
    for (int d = 0; d < dim; ++d) os << (d ? " " : "") << num(c[static_cast<std::ptrdiff_t>(i) * stride + d] / w);
    os << '\n';
  }
  os << "  </coefs>\n";
}

template <int D>
void put(std::ostream& os, const TensorSpline<D>& s, int id) {
  os << " <Geometry type=\"Tensor" << (s.is_rational() ? "Nurbs" : "BSpline") << D << "\" id=\"" << id << "\">\n";
  if (s.is_rational()) {
    os << "  <Basis type=\"TensorNurbsBasis" << D << "\">\n";
    put_tensor_basis<D>(os, s.knot_vectors(), "   ");
    os << "   <weights>";
    for (int i = 0; i < s.num_coefs(); ++i) os << num(s.weight(i)) << ' ';
    os << "</weights>\n  </Basis>\n";
  } else {
    put_tensor_basis<D>(os, s.knot_vectors(), "  ");
  }
  put_coefs(os, s.coefs().data(), s.num_coefs(), s.dim(), s.stride());
  os << " </Geometry>\n";
}

template <int D>
void put(std::ostream& os, const HierarchicalSpline<D>& s, int id) {
  require(!s.is_rational(), "gismo xml: rational hierarchical splines have no G+Smo type");
  const auto& sp = s.space();
  const auto& h = sp.hierarchy();
  const bool thb = sp.basis() == HierarchicalBasis::thb;
  os << " <Geometry type=\"" << (thb ? "THB" : "HB") << "Spline" << D << "\" id=\"" << id << "\">\n";
  const bool manual = h.dyadic_from() > 1;
  os << "  <Basis type=\"" << (thb ? "THB" : "HB") << "SplineBasis" << D << "\" manualLevels=\"" << (manual ? "true" : "false") << "\">\n";
  for (int l = 0; l < (manual ? h.dyadic_from() : 1); ++l) {
    std::array<KnotVector, D> kv;
    for (int k = 0; k < D; ++k) kv[static_cast<std::size_t>(k)] = h.knots(l, k);
    std::ostringstream t;
    put_tensor_basis<D>(t, kv, "   ");
    std::string text = t.str();
    if (manual) text.insert(text.find('>'), " level=\"" + std::to_string(l) + "\"");
    os << text;
  }
  // The domain cells of each level that no finer domain covers (the leaves of G+Smo's box tree, whose union
  // over levels >= l is Omega^l), as boxes: runs of consecutive cells along u.
  for (int l = 1; l < sp.num_levels(); ++l) {
    const auto cells = sp.domain_cells(l);
    for (std::size_t i = 0; i < cells.size();) {
      const Ints<D> lo = unpack_key<D>(cells[i]);
      if (sp.is_refined(l, lo)) {
        ++i;
        continue;
      }
      Ints<D> hi = lo;
      ++hi[0];
      for (++i; i < cells.size() && cells[i] == pack_key<D>(hi) && !sp.is_refined(l, hi); ++i) ++hi[0];
      for (int k = 1; k < D; ++k) ++hi[k];
      os << "   <box level=\"" << l << "\">";
      for (int k = 0; k < D; ++k) os << lo[k] << ' ';
      for (int k = 0; k < D; ++k) os << hi[k] << (k + 1 < D ? " " : "");
      os << "</box>\n";
    }
  }
  os << "  </Basis>\n";
  put_coefs(os, s.coefs().data(), sp.num_basis(), s.dim(), s.stride());
  os << " </Geometry>\n";
}

}  // namespace

std::vector<GismoGeometry> parse_gismo_xml(std::string_view text, const std::string& name) {
  const Reader r{name};
  xmlResetLastError();
  std::unique_ptr<xmlDoc, DocDeleter> doc(xmlReadMemory(text.data(), static_cast<int>(text.size()), name.c_str(), nullptr,
                                                        XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING));
  if (!doc) {
    const xmlError* e = xmlGetLastError();
    std::string msg = e && e->message ? e->message : "unreadable XML";
    while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
    throw Error("gismo xml: " + name + (e ? ", line " + std::to_string(e->line) : std::string()) + ": malformed XML: " + msg);
  }
  const xmlNode* root = xmlDocGetRootElement(doc.get());
  if (!root || !Reader::is(root, "xml")) r.fail(root, "the root node must be <xml>");
  std::vector<GismoGeometry> out;
  for (const xmlNode* g : Reader::children(root, "Geometry")) out.push_back(r.geometry(g));
  if (out.empty()) r.fail(root, "no <Geometry> node");
  return out;
}

std::vector<GismoGeometry> read_gismo_xml(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  require(bool(in), "gismo xml: cannot open " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return parse_gismo_xml(s.str(), path);
}

std::string gismo_xml_text(const std::vector<GismoGeometry>& geometries) {
  std::ostringstream os;
  os << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<xml>\n";
  for (std::size_t i = 0; i < geometries.size(); ++i)
    std::visit([&](const auto& g) { put(os, g, static_cast<int>(i)); }, geometries[i]);
  // A multipatch: the patches are the geometries above (G+Smo lists them by id).
  auto par_dim = [](const GismoGeometry& g) { return g.index() == 0 || g.index() == 2 ? 2 : 3; };
  bool same = true;
  for (const auto& g : geometries) same = same && par_dim(g) == par_dim(geometries.front());
  if (geometries.size() > 1 && same)
    os << " <MultiPatch parDim=\"" << par_dim(geometries.front()) << "\" id=\"" << geometries.size()
       << "\">\n  <patches type=\"id_range\">0 " << geometries.size() - 1 << "</patches>\n </MultiPatch>\n";
  os << "</xml>\n";
  return os.str();
}

void write_gismo_xml(const std::string& path, const std::vector<GismoGeometry>& geometries) {
  const std::string text = gismo_xml_text(geometries);
  write_file_atomically(path, [&](std::ostream& os) { os << text; });
}

}  // namespace trivar::io
