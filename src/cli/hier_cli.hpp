#pragma once
// Hierarchical splines on the command line: G+Smo files (.xml) holding THBSpline / HBSpline geometries.
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "trivar/hier/any_hierarchical_spline.hpp"
#include "trivar/io/lr_vtk.hpp"

namespace trivar::cli {

using AnyHierarchical = AnyHierarchicalSpline;

// The hierarchical splines of `path` when it is a .xml file whose geometries are hierarchical, or nothing (a
// .xml file of tensor geometries, another extension). Throws trivar::Error for a .xml file that does not parse
// or mixes tensor and hierarchical geometries.
std::optional<std::vector<AnyHierarchical>> read_hierarchical_if_any(const std::string& path);
// `info` text: kind, basis, degrees, levels, functions per level, elements, domain.
void print_hierarchical_info(const std::string& file, const std::vector<AnyHierarchical>& objects);
// Writes hierarchical splines to a G+Smo .xml file, a .vtu file (vtk: the cell kind) or a STEP file (their HB
// form, io/step/geometry_writer.hpp); any other extension throws "<command>: ...".
void write_hierarchical_file(const std::string& path, const std::vector<AnyHierarchical>& objects,
                             const std::string& command, const io::LRVtkOptions& vtk = {});

}  // namespace trivar::cli
