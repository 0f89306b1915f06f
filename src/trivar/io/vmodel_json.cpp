#include "trivar/io/vmodel_json.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "trivar/core/error.hpp"
#include "trivar/io/json_format.hpp"
#include "trivar/io/trimmed_json.hpp"

namespace trivar::io {

namespace {

using json = nlohmann::json;

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw Error(where + ": " + what); }

const json& member(const json& j, const char* key, const std::string& where) {
  const auto it = j.find(key);
  if (it == j.end()) fail(where, std::string("missing key \"") + key + "\"");
  return *it;
}

void only_keys(const json& j, std::initializer_list<const char*> keys, const std::string& where) {
  for (const auto& item : j.items())
    if (std::none_of(keys.begin(), keys.end(), [&](const char* key) { return item.key() == key; }))
      fail(where, "unexpected key \"" + item.key() + "\"");
}

const char* space_name(Attribute::Space s) { return s == Attribute::Space::model ? "model" : "parametric"; }

json attribute_json(const Attribute& a) {
  switch (a.kind()) {
    case Attribute::Kind::constant:
      return {{"kind", "constant"}, {"values", a.values()}};
    case Attribute::Kind::field: {
      json s = to_json(AnySpline(*a.spline()));
      s.erase("trivar");
      return {{"kind", "field"}, {"spline", std::move(s)}};
    }
    case Attribute::Kind::expression: {
      json c = json::array();
      for (const Expression& e : a.expressions()) c.push_back(e.text());
      return {{"kind", "expression"}, {"space", space_name(a.space())}, {"components", std::move(c)}};
    }
  }
  throw Error("attribute of unknown kind");
}

TensorSpline<3> volume_from_json(json j, const std::string& where) {
  if (j.is_object() && !j.contains("trivar")) j["trivar"] = 1;
  AnySpline s = spline_from_json(j, where);
  if (parametric_dimension(s) != 3) fail(where, "expected a volume");
  return std::get<TensorSpline<3>>(std::move(s));
}

Attribute attribute_from_json(const json& j, const std::string& where) {
  if (!j.is_object()) fail(where, std::string("expected an object, got ") + j.type_name());
  const json& kind = member(j, "kind", where);
  try {
    if (kind == "constant") {
      only_keys(j, {"kind", "values"}, where);
      const json& v = member(j, "values", where);
      if (!v.is_array() || v.empty()) fail(where + ": values", "expected a non-empty array of numbers");
      std::vector<double> values;
      for (const json& x : v) {
        if (!x.is_number()) fail(where + ": values", std::string("expected a number, got ") + x.type_name());
        values.push_back(x.get<double>());
      }
      return Attribute::constant(std::move(values));
    }
    if (kind == "field") {
      only_keys(j, {"kind", "spline"}, where);
      return Attribute::field(volume_from_json(member(j, "spline", where), where + ": spline"));
    }
    if (kind == "expression") {
      only_keys(j, {"kind", "space", "components"}, where);
      const json& space = member(j, "space", where);
      if (space != "model" && space != "parametric")
        fail(where + ": space", "expected \"model\" or \"parametric\", got " + space.dump());
      const json& c = member(j, "components", where);
      if (!c.is_array() || c.empty()) fail(where + ": components", "expected a non-empty array of strings");
      std::vector<std::string> components;
      for (const json& x : c) {
        if (!x.is_string()) fail(where + ": components", std::string("expected a string, got ") + x.type_name());
        components.push_back(x.get<std::string>());
      }
      return Attribute::expression(components,
                                   space == "model" ? Attribute::Space::model : Attribute::Space::parametric);
    }
  } catch (const Error& e) {
    // Messages of the attribute constructors do not know the JSON path.
    const std::string what = e.what();
    if (what.rfind(where, 0) == 0) throw;
    fail(where, what);
  }
  fail(where + ": kind", "expected \"constant\", \"field\" or \"expression\", got " + kind.dump());
}

GlueOptions glue_from_json(const json& j, const std::string& where) {
  if (!j.is_object()) fail(where, std::string("expected an object, got ") + j.type_name());
  only_keys(j, {"relative_tolerance", "absolute_tolerance", "samples"}, where);
  GlueOptions o;
  const auto real = [&](const char* key, double& out) {
    if (!j.contains(key)) return;
    const json& x = j[key];
    if (!x.is_number() || !std::isfinite(x.get<double>()) || x.get<double>() < 0)
      fail(where + ": " + key, "expected a number >= 0, got " + x.dump());
    out = x.get<double>();
  };
  real("relative_tolerance", o.relative_tolerance);
  real("absolute_tolerance", o.absolute_tolerance);
  if (j.contains("samples")) {
    const json& x = j["samples"];
    if (!x.is_number_integer() || x.get<long long>() < 2 || x.get<long long>() > 1000)
      fail(where + ": samples", "expected an integer in [2, 1000], got " + x.dump());
    o.samples = static_cast<int>(x.get<long long>());
  }
  return o;
}

std::string hex_colour(const Rgba& c) {
  char buf[10];
  std::snprintf(buf, sizeof buf, "#%02X%02X%02X%02X", c.r, c.g, c.b, c.a);
  return buf;
}

Rgba colour_from_json(const json& j, const std::string& where) {
  const auto hex = [](char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  const std::string s = j.is_string() ? j.get<std::string>() : std::string();
  bool ok = (s.size() == 7 || s.size() == 9) && s[0] == '#';
  for (std::size_t i = 1; ok && i < s.size(); ++i) ok = hex(s[i]) >= 0;
  if (!ok) fail(where, "expected a colour \"#RRGGBB\" or \"#RRGGBBAA\", got " + j.dump());
  const auto byte = [&](std::size_t i) { return static_cast<std::uint8_t>(16 * hex(s[i]) + hex(s[i + 1])); };
  return {byte(1), byte(3), byte(5), s.size() == 9 ? byte(7) : std::uint8_t{255}};
}

MaterialTable materials_from_json(const json& j, const std::string& where) {
  if (!j.is_array()) fail(where, std::string("expected an array of materials, got ") + j.type_name());
  MaterialTable t;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string at = where + "[" + std::to_string(i) + "]";
    if (!j[i].is_object()) fail(at, std::string("expected an object, got ") + j[i].type_name());
    only_keys(j[i], {"name", "color"}, at);
    const json& name = member(j[i], "name", at);
    if (!name.is_string()) fail(at + ": name", "expected a string, got " + name.dump());
    try {
      t.add({name.get<std::string>(), colour_from_json(member(j[i], "color", at), at + ": color")});
    } catch (const Error& e) {
      const std::string what = e.what();
      if (what.rfind(at, 0) == 0) throw;
      fail(at, what);
    }
  }
  return t;
}

}  // namespace

bool is_vmodel_json(const json& j) { return j.is_object() && j.contains("kind") && j["kind"] == "vmodel"; }

json to_json(const VModel& model, const GlueOptions& opts) {
  json cells = json::array();
  for (const VCell& c : model.cells()) {
    json geometry = to_json(AnySpline(c.geometry()));
    geometry.erase("trivar");
    json attributes = json::object();
    for (const auto& [name, a] : c.attributes()) attributes[name] = attribute_json(a);
    json cell{{"geometry", std::move(geometry)}, {"attributes", std::move(attributes)}};
    if (c.is_trimmed()) cell["trim"] = to_json(c.trim()->boundary());
    cells.push_back(std::move(cell));
  }
  json doc{{"trivar", 1},
           {"kind", "vmodel"},
           {"glue",
            {{"relative_tolerance", opts.relative_tolerance},
             {"absolute_tolerance", opts.absolute_tolerance},
             {"samples", opts.samples}}},
           {"cells", std::move(cells)}};
  if (!model.materials().empty()) {
    json mats = json::array();
    for (const Material& m : model.materials().materials()) mats.push_back({{"name", m.name}, {"color", hex_colour(m.colour)}});
    doc["materials"] = std::move(mats);
  }
  if (model.is_glued()) {
    const VTopology& t = model.topology();
    doc["summary"] = {{"cells", model.num_cells()},
                      {"shared_surfaces", t.num_shared_surfaces()},
                      {"boundary_surfaces", t.num_boundary_surfaces()},
                      {"curves", t.curves.size()},
                      {"points", t.points.size()},
                      {"non_conforming_faces", t.non_conforming.size()}};
  }
  return doc;
}

VModel vmodel_from_json(const json& j, const std::string& where) {
  if (!is_vmodel_json(j)) fail(where, "expected \"kind\": \"vmodel\"");
  only_keys(j, {"trivar", "kind", "glue", "materials", "cells", "summary"}, where);
  const GlueOptions opts = j.contains("glue") ? glue_from_json(j["glue"], where + ": glue") : GlueOptions{};
  const json& cells = member(j, "cells", where);
  if (!cells.is_array() || cells.empty()) fail(where + ": cells", "expected a non-empty array of cells");
  VModel model;
  if (j.contains("materials")) model.set_materials(materials_from_json(j["materials"], where + ": materials"));
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const std::string at = where + ": cells[" + std::to_string(i) + "]";
    const json& c = cells[i];
    if (!c.is_object()) fail(at, std::string("expected an object, got ") + c.type_name());
    only_keys(c, {"geometry", "attributes", "trim"}, at);
    TensorSpline<3> geometry = volume_from_json(member(c, "geometry", at), at + ": geometry");
    if (geometry.dim() != 3) fail(at + ": geometry", "expected control dimension 3, got " + std::to_string(geometry.dim()));
    VCell cell = [&] {
      if (!c.contains("trim")) return VCell(std::move(geometry));
      try {
        return VCell(std::move(geometry),
                     std::make_shared<const TrimmedSolid>(trimmed_boundary_from_json(c["trim"], at + ": trim")));
      } catch (const Error& e) {
        // Structural errors already name their JSON path; geometric ones (TrimmedSolid) get it here.
        if (std::string(e.what()).rfind(at, 0) == 0) throw;
        fail(at + ": trim", e.what());
      }
    }();
    if (c.contains("attributes")) {
      const json& attrs = c["attributes"];
      if (!attrs.is_object()) fail(at + ": attributes", std::string("expected an object, got ") + attrs.type_name());
      for (const auto& [name, a] : attrs.items()) cell.set_attribute(name, attribute_from_json(a, at + ": attributes: " + name));
    }
    model.add_cell(std::move(cell));
  }
  try {
    model.glue(opts);
  } catch (const Error& e) {
    fail(where, e.what());
  }
  return model;
}

VModel read_vmodel(const std::string& path) { return vmodel_from_json(read_json_document(path), path); }

void write_vmodel(const std::string& path, const VModel& model, const GlueOptions& opts) {
  require(model.num_cells() > 0, path + ": nothing to write (the model has no cells)");
  write_json_document(path, to_json(model, opts));
}

}  // namespace trivar::io
