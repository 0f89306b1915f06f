#pragma once
// Elastic materials from a V-model's cell attributes, so one model file carries the geometry and the
// materials of its analysis: "youngs_modulus", "poisson_ratio" and "density", each a scalar constant or a
// scalar expression in model coordinates x, y, z (a graded material). A cell without one of them takes the
// default's value.
#include <functional>

#include "trivar/iga/elasticity.hpp"

namespace trivar {

class VModel;

// The material of patch (cell) p at model point x, for ElasticityProblem::material_at. Throws trivar::Error
// naming the cell and attribute for an attribute that is not scalar or is a spline field or a parametric
// expression (their values depend on the cell parameter, which the assembly does not know), or when a
// constant material is not valid().
std::function<ElasticMaterial(int patch, const double* x)> cell_materials(const VModel& model,
                                                                          const ElasticMaterial& defaults);

}  // namespace trivar
