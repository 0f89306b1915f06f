#pragma once
// T-splines in STEP files, two ways.
//
// 1. The entities of Xiao et al. 2016 (seed 002), as its prototype's tsm2stp writes them (FILE_SCHEMA
//    'integrated_cnc_schema', AP238):
//      T_SPLINE_SURFACE(name, degree_s, degree_t, rational, #T_IMAGE, #T_CONNECT, #T_POINTSET)
//      T_IMAGE(name, (T_FACEs), (T_LINKs), (T_EDGEs), (T_VERTEXs))
//      T_VERTEX(name, #POINT_ON_SURFACE(name, #T_IMAGE, s, t), north, west, south, east T_LINK or $)
//      T_EDGE(name, #start, #end, left T_FACE or $, right T_FACE or $, boundary)
//      T_LINK(name, *, *, #T_EDGE, sense)
//      T_FACE(name, (FACE_BOUND(name, EDGE_LOOP(name, (T_LINKs)), .T.)))
//      T_EDGE_CONDITION(name, #T_EDGE, flag)
//      T_CONNECT(name, (T_NODE_V4s)); T_NODE_V4(name, #anchor, #RATIONAL_POINT, north, west, south, east)
//      (the anchor a T_VERTEX, T_LINK or T_FACE by the degree parities)
//      T_POINTSET(name, (RATIONAL_POINTs)); RATIONAL_POINT(name, (x, y, z), weight)
//    The three layers are written in their own order, so a trivar file reads back to the same TSpline.
//    Edges listed from the larger to the smaller parameter (as the prototype does) are turned round, their
//    links' senses with them.
// 2. ISO 10303-42: the blending functions as a (RATIONAL_)LOCALLY_REFINED_SPLINE_SURFACE with scaling
//    factors 1 and the locally_refined_spline_type of the classification (tspline/classification.hpp), which
//    any Part 42 reader evaluates; read back into the blending-function form of a T-spline (TSplineSurface).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "trivar/io/step/exchange_file.hpp"
#include "trivar/lr/lr_bspline.hpp"
#include "trivar/tspline/t_spline.hpp"

namespace trivar::io::step {

struct StepTSpline {
  std::uint64_t id = 0;
  std::string name;
  std::string entity;            // T_SPLINE_SURFACE or the Part 42 keyword
  std::string type;              // locally_refined_spline_type (Part 42 form), empty for T_SPLINE_SURFACE
  std::optional<TSpline> layers; // T_SPLINE_SURFACE: the three layers
  Ints<2> degrees{};             // Part 42 form: the blending functions, homogeneous (w x, w y, w z, w)
  std::vector<LRBSpline<2>> basis;
};

// The keywords of the seed-002 T-spline entities (for the reader's keep filter), and the generic entities they
// use (RATIONAL_POINT, EDGE_LOOP, FACE_BOUND, POINT_ON_SURFACE), which a reader keeps only when the file has a
// T_SPLINE_SURFACE (in B-rep files they are many and not needed).
bool is_t_spline_keyword(std::string_view keyword);
bool is_t_spline_part_keyword(std::string_view keyword);
// The locally_refined_spline_type values that name T-splines.
bool is_t_spline_type(std::string_view type);

// Adds the T-spline's three layers; returns the T_SPLINE_SURFACE id.
std::uint64_t add_t_spline(ExchangeFile& file, const TSpline& ts, const std::string& name = "");

// Every T_SPLINE_SURFACE of the file, mapped; throws trivar::Error "name:line:column: #id: KEYWORD: message"
// for a missing or wrong reference, a wrong parameter, or layers that do not form a valid T-spline.
std::vector<StepTSpline> read_t_spline_surfaces(const ExchangeFile& file, const std::string& name);

enum class TSplineStepForm { t_spline_entities, part42 };

// A complete file: the seed-002 entities (schema integrated_cnc_schema) or a Part 42 locally refined surface in
// an AP242 shape representation.
ExchangeFile t_spline_exchange_file(const TSpline& ts, TSplineStepForm form, const std::string& name = "");
void write_t_spline_step(const std::string& path, const TSpline& ts, TSplineStepForm form,
                         const std::string& time_stamp = "");

}  // namespace trivar::io::step
