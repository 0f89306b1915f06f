#pragma once
// VTK output of a V-model: every cell's trivariate as one piece of a .vtu file (see vtk_writer.hpp for the
// modes), with point data "vcell" (the cell index) and one array per attribute name, evaluated at every
// point's cell parameters. Cells without an attribute get NaN there (ParaView shows them as missing); an
// attribute with fewer components in some cell is padded with NaN.
#include <string>

#include "trivar/io/vtk_writer.hpp"
#include "trivar/model/vmodel.hpp"

namespace trivar::io {

void write_vmodel_vtu(const std::string& path, const VModel& model, const VtkOptions& opts = {});

}  // namespace trivar::io
