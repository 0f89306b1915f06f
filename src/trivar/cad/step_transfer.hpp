#pragma once
// Internal to the cad layer (includes OpenCASCADE): the STEP transfer with trivar's choice of the kernel's
// shape healing.
//
// The kernel's STEP transfer heals every shape it reads: without a STEP resource file in its search path (as
// installed by Debian) its built-in fallback, one ShapeFix_Shape with the default modes. Two of its wire fixes
// cost time quadratic in the loops of one face, whether or not anything needs fixing: ShapeFix_Wire's fix of
// non-adjacent intersecting edges re-applies the face's replacements for each of its wires, and ShapeFix_Face's
// fix of intersecting wires tests pairs of wires. On a plate with 784 hole loops in one face they were 80 % of
// the transfer's healing (11.6e9 of 14.4e9 instructions). Both defects are ones the validity check after the transfer
// finds (BRepCheck_Wire's self-intersection, BRepCheck_Face's intersecting wires); import_step then heals the
// solid with the kernel's full default ShapeFix_Shape, both fixes included. So the transfer runs that healing as
// a ShapeProcess sequence (the kernel's documented read.step.resource.name / read.step.sequence parameters)
// minus those two modes, and a file that needs them still gets them.
#include <STEPControl_Reader.hxx>

namespace trivar::cad {

// reader.TransferRoots() with the healing above; returns the number of roots transferred. The kernel keeps its
// healing parameters in process-wide state: they are switched for the duration of the call (serialised with
// other calls of this function) and restored afterwards.
int transfer_roots(STEPControl_Reader& reader);

}  // namespace trivar::cad
