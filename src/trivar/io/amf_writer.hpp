#pragma once
// AMF (ISO/ASTM 52915, version 1.1) of a triangle mesh with materials: one object, one volume.
//
// Materials k = 0..m-1 get AMF ids k + 1 (id 0 is AMF's void) with a name and colour. Grading: AMF expresses a
// graded material as a composite material whose proportions are formulas in x, y, z (model units), so the
// volume refers either to one base material or to a composite material (id m + 1) built from one formula per
// material; AMF normalises the proportions. AMF has no per-vertex material mixtures: per-vertex fractions are
// recorded as per-vertex <color> (the fraction-weighted mix of the material colours), which shows the grading
// but does not define it. The object has id m + 2.
//
// Plain XML, or (zip = true) a ZIP archive holding one entry named after the file, keeping the .amf extension
// as the standard allows. Coordinates are written as the shortest text that reads back to the same double.
#include <span>
#include <string>
#include <vector>

#include "trivar/model/material_table.hpp"
#include "trivar/model/triangle_mesh.hpp"

namespace trivar::io {

struct AmfGrading {
  int base_material = 0;              // the volume's material when `formulas` is empty
  std::vector<std::string> formulas;  // empty, or one proportion formula in x, y, z per material
};

struct AmfOptions {
  bool zip = false;
};

// vertex_fractions: empty, or materials.size() values per vertex (divided by their sum) for the vertex
// colours. Throws trivar::Error for an empty mesh or material table, a vertex index out of range, a non-finite
// coordinate, a base material out of range, a formula count other than m or an empty formula, a fraction
// count other than vertices x materials, fractions that break the rule of material_fractions.hpp, or a write
// failure; nothing is written then.
void write_amf(const std::string& path, const TriangleMesh& mesh, const MaterialTable& materials,
               const AmfGrading& grading, std::span<const double> vertex_fractions = {},
               const AmfOptions& options = {});

}  // namespace trivar::io
