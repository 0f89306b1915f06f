#include "trivar/model/cylinder.hpp"

#include "trivar/model/cone.hpp"

namespace trivar {

CellComplex make_cylinder(const CylinderSpec& spec) {
  return make_cone({.bottom_radius = spec.radius, .top_radius = spec.radius, .height = spec.height, .core = spec.core});
}

}  // namespace trivar
