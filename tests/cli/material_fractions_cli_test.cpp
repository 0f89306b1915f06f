// One rule for material fractions: info, slice and export to 3MF and AMF reject the same bad model with the
// same message, and write nothing.
#include "cli/cli_fixture.hpp"

using namespace cli_test;

namespace {

// The unit cube as a one-cell V-model of two materials whose "material" attribute is `material`.
std::string cube_model(const nlohmann::json& material) {
  nlohmann::json cell{{"geometry", nlohmann::json::parse(unit_cube_json(false))}};
  cell["geometry"].erase("trivar");
  cell["attributes"]["material"] = material;
  const nlohmann::json materials = {{{"name", "A"}, {"color", "#FF0000"}}, {{"name", "B"}, {"color", "#0000FF"}}};
  return nlohmann::json{{"trivar", 1}, {"kind", "vmodel"}, {"materials", materials}, {"cells", {cell}}}.dump();
}

}  // namespace

class MaterialFractionsCli : public Cli {};

TEST_F(MaterialFractionsCli, EveryConsumerRejectsTheSameBadFractionsAlike) {
  const std::string rule = "; fractions must be finite and >= 0 with a positive sum";
  const std::vector<std::pair<nlohmann::json, std::string>> cases = {
      {{{"kind", "constant"}, {"values", {0, 0}}}, "material fractions (0, 0): sum to 0"},
      {{{"kind", "constant"}, {"values", {-0.5, 1.5}}}, "material fractions (-0.5, 1.5): fraction 0 is negative"},
      {{{"kind", "expression"}, {"space", "model"}, {"components", {"0/0", "1"}}},
       "material fractions (NaN, 1): fraction 0 is not finite"},
      {{{"kind", "expression"}, {"space", "model"}, {"components", {"x - 0.5", "1"}}},
       "material fractions (-0.5, 1): fraction 0 is negative"},
  };
  for (const auto& [material, problem] : cases) {
    write("m.json", cube_model(material));
    const std::string expected = "trivar: error: cell 0 at parameter (0, 0, 0): " + problem + rule + "\n";
    for (const char* args : {"info m.json", "slice m.json --out s", "export m.json m.3mf", "export m.json m.amf"}) {
      const auto before = listing();
      const Result r = run(args);
      EXPECT_EQ(r.code, 1) << args;
      EXPECT_EQ(r.err, expected) << args;
      EXPECT_EQ(listing(), before) << args << " left files behind";
    }
  }
  // Fractions that are only proportions are fine: (2, 1) is two thirds of material 0.
  write("m.json", cube_model({{"kind", "constant"}, {"values", {2, 1}}}));
  ok("export m.json m.3mf");
}
