#pragma once
// B-rep solids of a STEP file (AP203 / AP214 / AP242) read with OpenCASCADE and mapped to trivar types: every
// face becomes an exact NURBS patch (TensorSpline<2>) with its trimming loops (parameter-space curves and the
// 3D edges they run along), orientation and tolerance, and each solid a TrimmedSolid whose watertight mesh
// comes from the kernel's trimmed-face tessellation. Nothing of OpenCASCADE appears in this header: the cad
// layer is the only place its types exist. Nothing is dropped silently: the report counts what is not part
// of a solid and names the faces that could not be mapped and the repairs that were made.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "trivar/model/closure_defect.hpp"
#include "trivar/model/trimmed_solid.hpp"

namespace trivar::cad {

struct ImportOptions {
  // Largest distance of the boundary mesh from the faces, in model units; 0 picks 1e-3 of the part's
  // bounding-box diagonal.
  double chordal_tolerance = 0;
  // Largest angle between the normals of neighbouring mesh triangles on a face, in radians.
  double angular_tolerance = 0.5;
  // Also compute OpenCASCADE's own volume of each solid (BRepGProp's adaptive rule to 1e-9 on the faces as read),
  // as an independent cross-check of trivar's exact-boundary volume; extra time, so only on request.
  bool kernel_volume = false;
};

// A face that could not become a trimmed NURBS patch, and why.
struct UnmappedFace {
  std::string name;    // "#812 ADVANCED_FACE" (STEP instance), or "solid 2 face 17" when the file says nothing
  std::string reason;
};

struct BrepReport {
  std::string file;
  std::string originating_system;
  int solids = 0, shells = 0, faces = 0, edges = 0, vertices = 0;  // distinct topological entities
  // Faces per source surface kind: plane, cylinder, cone, sphere, torus, bspline, bezier, revolution,
  // extrusion, offset, other.
  std::map<std::string, int> faces_by_kind;
  // What is not part of a solid: shells, faces, edges and vertices outside every solid, one line each kind
  // ("2 shells outside solids (1 open: 4 free edges)").
  std::vector<std::string> not_solid;
  std::vector<UnmappedFace> unmapped;
  std::vector<std::string> repairs;  // "solid 1: 3 edges without parameter-space curves repaired"
  // One line per mapped solid whose faces do not close beyond their tolerances (ClosureDefect::closed()):
  // open_boundary_warning().
  std::vector<std::string> open_boundaries;
};

struct ImportedSolid {
  std::string name;                            // "solid 0" or the STEP instance ("#48 MANIFOLD_SOLID_BREP 'part'")
  std::shared_ptr<const TrimmedSolid> solid;   // null when a face could not be mapped (see the report)
  // OpenCASCADE's volume of the solid as read (BRepGProp), when ImportOptions::kernel_volume asked for it.
  std::optional<double> kernel_volume;
  // How far the mapped faces are from closing (closure_defect.hpp), when the solid is mapped.
  std::optional<ClosureDefect> closure;
};

struct StepImport {
  BrepReport report;
  std::vector<ImportedSolid> solids;
};

// The report's line for a solid whose boundary does not close: "<solid>: the boundary does not close (|A| = ...,
// ... of its area): the volume depends on the reference point of the divergence theorem by up to ...".
std::string open_boundary_warning(const std::string& solid, const ClosureDefect& d);

// Reads and maps every solid. Throws trivar::Error "<path>: ..." (one line) for an unreadable file, a file the
// kernel cannot transfer, or a solid that stays invalid after repair. Solids with unmapped faces are returned
// without a TrimmedSolid and listed in the report.
StepImport import_step(const std::string& path, const ImportOptions& opts = {});

}  // namespace trivar::cad
