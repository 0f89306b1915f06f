#include "trivar/io/step/step_file.hpp"

#include <unordered_map>

#include "trivar/io/step/parser.hpp"
#include "trivar/io/step/writer.hpp"

namespace trivar::io::step {

namespace {

bool is_curve_wrapper(std::string_view k) {
  return k == "SURFACE_CURVE" || k == "SEAM_CURVE" || k == "INTERSECTION_CURVE";
}

bool keep(std::string_view k) {
  return is_geometry_keyword(k) || k == "ADVANCED_FACE" || k == "FACE_SURFACE" || k == "EDGE_CURVE" ||
         is_curve_wrapper(k);
}

std::uint64_t referenced(const Record& r, std::size_t index) {
  if (index >= r.params.size()) return 0;
  const auto* ref = r.params[index].get_if<Reference>();
  return ref ? ref->id : 0;
}

StepContents map(const ExchangeFile& f, const std::string& name) {
  StepContents out;
  out.header = f.header;
  for (const auto& [k, n] : f.skipped()) out.entities[k].skipped += n;
  // Users of geometry: face -> surface, edge -> curve (through one wrapper level).
  std::unordered_map<std::uint64_t, std::vector<std::uint64_t>> faces, edges;
  for (const Instance& in : f.instances()) {
    ++out.entities[in.type_name()].kept;
    if (in.complex) continue;
    const Record& r = in.records.front();
    if (r.keyword == "ADVANCED_FACE" || r.keyword == "FACE_SURFACE") {
      if (const auto s = referenced(r, 2)) faces[s].push_back(in.id);
    } else if (r.keyword == "EDGE_CURVE") {
      std::uint64_t c = referenced(r, 3);
      if (const Instance* w = f.find(c); w && !w->complex && is_curve_wrapper(w->records.front().keyword))
        c = referenced(w->records.front(), 1);
      if (c) edges[c].push_back(in.id);
    }
  }
  const GeometryReader reader(f, name);
  for (const Instance& in : f.instances()) {
    const GeometryKind kind = geometry_kind(in);
    if (kind == GeometryKind::none) continue;
    StepObject o{in.id, reader.name(in), kind, in.type_name(), {}, {}};
    if (auto it = faces.find(in.id); it != faces.end()) o.faces = it->second;
    if (auto it = edges.find(in.id); it != edges.end()) o.edges = it->second;
    switch (kind) {
      case GeometryKind::curve:
      case GeometryKind::lr_curve:
      case GeometryKind::surface:
      case GeometryKind::volume:
        out.splines.push_back(reader.tensor_spline(in));
        out.spline_info.push_back(std::move(o));
        break;
      default:  // locally refined surfaces and volumes
        out.lr_splines.push_back(reader.lr_spline(in));
        out.lr_info.push_back(std::move(o));
        break;
    }
  }
  return out;
}

}  // namespace

std::size_t StepContents::instance_count() const {
  std::size_t n = 0;
  for (const auto& [k, c] : entities) n += c.total();
  return n;
}

StepContents read_step(const std::string& path) {
  ReadOptions o;
  o.keep = keep;
  return map(read_exchange_file(path, o), path);
}

StepContents parse_step(std::string_view text, const std::string& name) {
  ReadOptions o;
  o.keep = keep;
  return map(parse_exchange_file(text, name, o), name);
}

void write_step(const std::string& path, const std::vector<AnySpline>& splines,
                const std::vector<AnyLRSpline>& lr_splines, const GeometryFileOptions& options,
                const std::string& time_stamp) {
  ExchangeFile f = geometry_exchange_file(splines, lr_splines, options);
  f.header.name = path.substr(path.find_last_of('/') + 1);
  WriteOptions w;
  w.time_stamp = time_stamp;
  write_exchange_file(path, f, w);
}

}  // namespace trivar::io::step
