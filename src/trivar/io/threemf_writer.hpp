#pragma once
// 3MF (core 1.4 + materials extension 1.2) of a graded triangle mesh: one object whose vertices carry composite
// materials (m:compositematerials over one basematerials group), so a consumer interpolates the mixture across
// each triangle. trivar writes the XML itself because Debian's lib3mf 1.8 has no composite materials.
//
// Package (OPC zip): [Content_Types].xml, _rels/.rels (start part) and 3D/3dmodel.model. Resources: basematerials
// id 1 (name, displaycolor #RRGGBB or #RRGGBBAA), m:compositematerials id 2 over all base materials with one
// composite per distinct vertex mixture, object id 3 (pid 2) whose triangles carry pid, p1, p2, p3; a build item
// for object 3. Unit millimeter; coordinates and mixing values are written as the shortest text that reads back
// to the same double. The materials extension is listed in requiredextensions: a consumer that cannot blend
// must refuse the file rather than print it in one material.
#include <span>
#include <string>

#include "trivar/model/material_table.hpp"
#include "trivar/model/triangle_mesh.hpp"

namespace trivar::io {

// vertex_fractions holds materials.size() values per vertex (vertex-major); each vertex's values are divided by
// their sum. Throws trivar::Error for an empty mesh or material table, a vertex index out of range, a non-finite
// coordinate, a fraction count that is not vertices x materials, fractions that break the rule of
// material_fractions.hpp, or a write failure; nothing is written then.
void write_3mf(const std::string& path, const TriangleMesh& mesh, const MaterialTable& materials,
               std::span<const double> vertex_fractions, const std::string& object_name = "trivar part");

}  // namespace trivar::io
