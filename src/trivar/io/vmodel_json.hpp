#pragma once
// trivar's native JSON V-model format (schema in docs/formats.md):
//   {"trivar": 1, "kind": "vmodel",
//    "glue": {"relative_tolerance": 1e-7, "absolute_tolerance": 0, "samples": 5},
//    "materials": [{"name": "VeroCyan", "color": "#00FFFFFF"}, ..],    optional, by component index
//    "cells": [ {"geometry": {<volume object>},
//                "attributes": {"density": {"kind": "constant", "values": [..]},
//                               "material": {"kind": "field", "spline": {<volume object, any dim>}},
//                               "temperature": {"kind": "expression", "space": "model"|"parametric",
//                                               "components": ["x + y", ..]}},
//                "trim": {<trimming boundary, trimmed_json.hpp>}} ],      trimmed cells only
//    "summary": {...}}                      written for readers; ignored on input
// The topology is not stored: it is a function of the cells and the glue options, and reading glues again.
#include <string>

#include <nlohmann/json.hpp>

#include "trivar/model/vmodel.hpp"

namespace trivar::io {

// Glue options are stored so that reading reproduces the topology; `opts` are the ones the model was glued
// with (the default when it is not glued).
nlohmann::json to_json(const VModel& model, const GlueOptions& opts = {});

// Validates, builds and glues. Errors name `where` and the JSON path ("m.json: cells[2]: attributes: rho: ...").
VModel vmodel_from_json(const nlohmann::json& j, const std::string& where);

// True when the JSON document is a V-model (so a reader can dispatch between spline files and models).
bool is_vmodel_json(const nlohmann::json& j);

VModel read_vmodel(const std::string& path);
void write_vmodel(const std::string& path, const VModel& model, const GlueOptions& opts = {});

}  // namespace trivar::io
