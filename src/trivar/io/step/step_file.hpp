#pragma once
// STEP files as containers of trivar geometry: read every spline curve, surface, volume and locally refined
// spline of an AP203 / AP214 / AP242 file (with the faces and edges that use them and statistics of
// everything else), and write splines and LR splines as a minimal AP242 file (geometry_writer.hpp).
//
// Reading keeps only what the mapper needs (spline entities and their parts, CARTESIAN_POINT, ADVANCED_FACE,
// FACE_SURFACE, EDGE_CURVE and the SURFACE_CURVE / SEAM_CURVE / INTERSECTION_CURVE wrappers between edges and
// their curves); everything else is skipped unparsed and counted. Unknown entities are never an error;
// invalid spline data, dangling references and references to the wrong type are (geometry_reader.hpp).
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "trivar/io/step/exchange_file.hpp"
#include "trivar/io/step/geometry_reader.hpp"
#include "trivar/io/step/geometry_writer.hpp"
#include "trivar/io/step/t_spline_step.hpp"

namespace trivar::io::step {

struct StepObject {
  std::uint64_t id = 0;        // instance id in the file
  std::string name;            // representation_item.name
  GeometryKind kind = GeometryKind::none;
  std::string entity;          // keyword, or the partial records joined by '+' for a complex instance
  std::vector<std::uint64_t> faces;  // ADVANCED_FACE / FACE_SURFACE instances whose face_geometry it is
  std::vector<std::uint64_t> edges;  // EDGE_CURVE instances whose edge_geometry it is (directly or via a
                                     // SURFACE_CURVE / SEAM_CURVE / INTERSECTION_CURVE)
};

struct EntityCount {
  std::size_t kept = 0, skipped = 0;
  std::size_t total() const { return kept + skipped; }
};

struct StepContents {
  Header header;
  std::vector<AnySpline> splines;     // file order; locally refined curves become B-spline curves
  std::vector<StepObject> spline_info;  // parallel to splines
  std::vector<AnyLRSpline> lr_splines;
  std::vector<StepObject> lr_info;      // parallel to lr_splines
  // T_SPLINE_SURFACEs (three layers) and locally refined surfaces whose type names a T-spline (blending
  // functions; they need not sum to one, so they are no LR splines), in file order.
  std::vector<StepTSpline> t_splines;
  std::map<std::string, EntityCount> entities;  // per keyword (complex instances: keywords joined by '+')
  // ADVANCED_FACE / FACE_SURFACE instances, and those whose surface is no spline (planes, cylinders, ...)
  // per surface entity: their geometry is not extracted.
  std::size_t faces = 0;
  std::map<std::string, std::size_t> unmapped_faces;
  std::vector<ReadWarning> warnings;  // what the reader accepted leniently (read_warnings.hpp)
  std::size_t instance_count() const;
  // "skipped 1169 of 1202 faces (surface not a spline): 812 PLANE, 301 CYLINDRICAL_SURFACE, ..." by
  // decreasing count; empty when every face's surface was extracted.
  std::string unmapped_faces_summary() const;
};

// `strict`: refuse the departures from ISO 10303-21 that are otherwise warnings (ReadOptions::strict).
StepContents read_step(const std::string& path, bool strict = false);
// From text in memory; `name` prefixes messages.
StepContents parse_step(std::string_view text, const std::string& name = "<memory>", bool strict = false);

// Writes geometry_exchange_file(splines, lr_splines, options) atomically. `time_stamp` empty: now.
void write_step(const std::string& path, const std::vector<AnySpline>& splines,
                const std::vector<AnyLRSpline>& lr_splines, const GeometryFileOptions& options = {},
                const std::string& time_stamp = "");
// The same with hierarchical splines (geometry_writer.hpp: their HB form, type .HIERARCHICAL_B_SPLINE.).
void write_step(const std::string& path, const std::vector<AnySpline>& splines,
                const std::vector<AnyLRSpline>& lr_splines, const std::vector<AnyHierarchicalSpline>& hierarchical,
                const GeometryFileOptions& options = {}, const std::string& time_stamp = "");

}  // namespace trivar::io::step
