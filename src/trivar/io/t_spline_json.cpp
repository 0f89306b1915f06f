#include "trivar/io/t_spline_json.hpp"

#include <fstream>

#include <nlohmann/json.hpp>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"

namespace trivar::io {

namespace {

constexpr const char* kAnchor[3] = {"vertex", "link", "face"};

}  // namespace

void write_t_spline_json(const std::string& path, const TSpline& ts) {
  validate(ts);
  nlohmann::json j;
  j["kind"] = "t_spline";
  j["name"] = ts.name;
  j["degrees"] = {ts.degrees[0], ts.degrees[1]};
  j["force_bezier"] = ts.force_bezier;
  auto& im = j["t_image"];
  im["vertices"] = nlohmann::json::array();
  for (const TVertex& v : ts.image.vertices) im["vertices"].push_back({v.s, v.t, v.links});
  im["edges"] = nlohmann::json::array();
  for (const TEdge& e : ts.image.edges) im["edges"].push_back({e.start, e.end});
  im["links"] = nlohmann::json::array();
  for (const TLink& l : ts.image.links) im["links"].push_back({l.edge, l.sense});
  im["faces"] = nlohmann::json::array();
  for (const TFace& f : ts.image.faces) im["faces"].push_back(f.loop);
  im["edge_conditions"] = nlohmann::json::array();
  for (const TEdgeCondition& c : ts.image.conditions) im["edge_conditions"].push_back({c.edge, c.flag});
  j["t_connect"] = nlohmann::json::array();
  for (const TNode& n : ts.connect.nodes)
    j["t_connect"].push_back({{"anchor", kAnchor[static_cast<int>(n.kind)]}, {"id", n.anchor}, {"point", n.point},
                              {"neighbours", n.neighbours}});
  j["t_pointset"] = nlohmann::json::array();
  for (const RationalPoint& p : ts.pointset.points) j["t_pointset"].push_back({p.xyz[0], p.xyz[1], p.xyz[2], p.w});
  write_file_atomically(path, [&](std::ostream& os) { os << j.dump(1) << '\n'; });
}

TSpline read_t_spline_json(const std::string& path) {
  std::ifstream in(path);
  require(in.good(), "cannot open " + path);
  TSpline ts;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    require(j.at("kind") == "t_spline", path + ": kind is not \"t_spline\"");
    ts.name = j.value("name", "");
    ts.degrees = {j.at("degrees").at(0).get<int>(), j.at("degrees").at(1).get<int>()};
    ts.force_bezier = j.value("force_bezier", true);
    const auto& im = j.at("t_image");
    for (const auto& v : im.at("vertices"))
      ts.image.vertices.push_back({v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<std::array<int, 4>>()});
    for (const auto& e : im.at("edges")) ts.image.edges.push_back({e.at(0).get<int>(), e.at(1).get<int>()});
    for (const auto& l : im.at("links")) ts.image.links.push_back({l.at(0).get<int>(), l.at(1).get<bool>()});
    for (const auto& f : im.at("faces")) ts.image.faces.push_back({f.get<std::vector<int>>()});
    for (const auto& c : im.value("edge_conditions", nlohmann::json::array()))
      ts.image.conditions.push_back({c.at(0).get<int>(), c.at(1).get<bool>()});
    for (const auto& n : j.at("t_connect")) {
      TNode x;
      const std::string a = n.at("anchor");
      require(a == "vertex" || a == "link" || a == "face", path + ": t_connect: anchor \"" + a + "\" is not vertex, link or face");
      x.kind = a == "vertex" ? TAnchorKind::vertex : a == "link" ? TAnchorKind::link : TAnchorKind::face;
      x.anchor = n.at("id");
      x.point = n.at("point");
      x.neighbours = n.at("neighbours").get<std::array<int, 4>>();
      ts.connect.nodes.push_back(x);
    }
    for (const auto& p : j.at("t_pointset"))
      ts.pointset.points.push_back({{p.at(0).get<double>(), p.at(1).get<double>(), p.at(2).get<double>()}, p.at(3).get<double>()});
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": " + e.what());
  }
  try {
    validate(ts);
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
  return ts;
}

}  // namespace trivar::io
