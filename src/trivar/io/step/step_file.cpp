#include "trivar/io/step/step_file.hpp"

#include <algorithm>
#include <unordered_map>

#include "trivar/io/step/parser.hpp"
#include "trivar/io/step/writer.hpp"

namespace trivar::io::step {

namespace {

bool is_curve_wrapper(std::string_view k) {
  return k == "SURFACE_CURVE" || k == "SEAM_CURVE" || k == "INTERSECTION_CURVE";
}

bool keep(std::string_view k) {
  return is_geometry_keyword(k) || is_t_spline_keyword(k) || k == "ADVANCED_FACE" || k == "FACE_SURFACE" || k == "EDGE_CURVE" ||
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
  out.warnings = f.warnings;
  for (const auto& [k, n] : f.skipped()) out.entities[k].skipped += n;
  if (f.point_count() > 0) out.entities["CARTESIAN_POINT"].kept += f.point_count();
  // Users of geometry: face -> surface, edge -> curve (through one wrapper level).
  std::unordered_map<std::uint64_t, std::vector<std::uint64_t>> faces, edges;
  // Faces whose surface is not mapped, by surface id; the entity is named once all instances are known.
  std::unordered_map<std::uint64_t, std::size_t> unmapped_surfaces;
  for (const Instance& in : f.instances()) {
    ++out.entities[in.type_name()].kept;
    if (in.complex) continue;
    const Record& r = in.records.front();
    if (r.keyword == "ADVANCED_FACE" || r.keyword == "FACE_SURFACE") {
      ++out.faces;
      if (const auto s = referenced(r, 2)) {
        faces[s].push_back(in.id);
        const Instance* surface = f.find(s);
        if (!surface || geometry_kind(*surface) == GeometryKind::none) ++unmapped_surfaces[s];
      }
    } else if (r.keyword == "EDGE_CURVE") {
      std::uint64_t c = referenced(r, 3);
      if (const Instance* w = f.find(c); w && !w->complex && is_curve_wrapper(w->records.front().keyword))
        c = referenced(w->records.front(), 1);
      if (c) edges[c].push_back(in.id);
    }
  }
  for (const ExchangeFile::Skipped& sk : f.skipped_instances())
    if (const auto it = unmapped_surfaces.find(sk.id); it != unmapped_surfaces.end()) {
      out.unmapped_faces[*sk.type_name] += it->second;
      unmapped_surfaces.erase(it);
    }
  for (const auto& [id, n] : unmapped_surfaces) {  // kept but not a spline (or not a surface at all)
    const Instance* surface = f.find(id);
    out.unmapped_faces[surface ? surface->type_name() : "?"] += n;
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
        if (kind == GeometryKind::lr_surface && is_t_spline_type(reader.locally_refined_type(in))) {
          LocallyRefinedSurfaceParts p = reader.locally_refined_surface_parts(in);
          StepTSpline t{in.id, o.name, o.entity, p.type, std::nullopt, p.degrees, std::move(p.basis)};
          for (auto& b : t.basis) {  // to (w x, w y, w z, w)
            const double w = p.rational ? b.coef.back() : 1.0;
            b.coef.resize(static_cast<std::size_t>(p.dim));
            b.coef.resize(3, 0.0);
            b.coef.push_back(w);
          }
          out.t_splines.push_back(std::move(t));
          break;
        }
        out.lr_splines.push_back(reader.lr_spline(in));
        out.lr_info.push_back(std::move(o));
        break;
    }
  }
  for (StepTSpline& t : read_t_spline_surfaces(f, name)) out.t_splines.push_back(std::move(t));
  std::stable_sort(out.t_splines.begin(), out.t_splines.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  return out;
}

}  // namespace

std::size_t StepContents::instance_count() const {
  std::size_t n = 0;
  for (const auto& [k, c] : entities) n += c.total();
  return n;
}

std::string StepContents::unmapped_faces_summary() const {
  std::size_t total = 0;
  std::vector<std::pair<std::string, std::size_t>> kinds(unmapped_faces.begin(), unmapped_faces.end());
  for (const auto& [k, n] : kinds) total += n;
  if (total == 0) return {};
  std::stable_sort(kinds.begin(), kinds.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  std::string s = "skipped " + std::to_string(total) + " of " + std::to_string(faces) + " faces (surface not a spline):";
  for (std::size_t k = 0; k < kinds.size(); ++k) s += (k ? ", " : " ") + std::to_string(kinds[k].second) + " " + kinds[k].first;
  return s;
}

namespace {

bool keep_with_t_spline_parts(std::string_view k) { return keep(k) || is_t_spline_part_keyword(k); }

bool has_t_spline_surface(const ExchangeFile& f) {
  for (const Instance& in : f.instances())
    if (in.is("T_SPLINE_SURFACE")) return true;
  return false;
}

}  // namespace

StepContents read_step(const std::string& path, bool strict) {
  ReadOptions o;
  o.keep = keep;
  o.compact_points = true;
  o.strict = strict;
  ExchangeFile f = read_exchange_file(path, o);
  if (has_t_spline_surface(f)) {  // read again keeping the generic parts of the T-spline entities
    o.keep = keep_with_t_spline_parts;
    f = read_exchange_file(path, o);
  }
  return map(f, path);
}

StepContents parse_step(std::string_view text, const std::string& name, bool strict) {
  ReadOptions o;
  o.keep = keep;
  o.compact_points = true;
  o.strict = strict;
  ExchangeFile f = parse_exchange_file(text, name, o);
  if (has_t_spline_surface(f)) {
    o.keep = keep_with_t_spline_parts;
    f = parse_exchange_file(text, name, o);
  }
  return map(f, name);
}

void write_step(const std::string& path, const std::vector<AnySpline>& splines,
                const std::vector<AnyLRSpline>& lr_splines, const GeometryFileOptions& options,
                const std::string& time_stamp) {
  write_step(path, splines, lr_splines, {}, options, time_stamp);
}

void write_step(const std::string& path, const std::vector<AnySpline>& splines,
                const std::vector<AnyLRSpline>& lr_splines, const std::vector<AnyHierarchicalSpline>& hierarchical,
                const GeometryFileOptions& options, const std::string& time_stamp) {
  ExchangeFile f = geometry_exchange_file(splines, lr_splines, hierarchical, options);
  f.header.name = path.substr(path.find_last_of('/') + 1);
  WriteOptions w;
  w.time_stamp = time_stamp;
  write_exchange_file(path, f, w);
}

}  // namespace trivar::io::step
