#pragma once
// Materials of a multi-material part (part of a V-model): a name and a display colour each. Their order is the material index
// used by fraction images, dithered label images, palettes and the 3MF/AMF writers.
#include <cstdint>
#include <string>
#include <vector>

#include "trivar/core/error.hpp"

namespace trivar {

struct Rgba {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
  friend bool operator==(const Rgba&, const Rgba&) = default;
};

struct Material {
  std::string name;
  Rgba colour;
};

// At most 255 materials, so a label image fits one byte per pixel with 0 left for "empty" (and a palette PNG
// holds the background plus every material). Names are non-empty and unique: file formats refer to them.
class MaterialTable {
public:
  static constexpr int max_materials = 255;

  MaterialTable() = default;
  explicit MaterialTable(std::vector<Material> materials) {
    for (auto& m : materials) add(std::move(m));
  }

  // Returns the new material's index; throws trivar::Error for an empty or repeated name or a full table.
  int add(Material m) {
    require(!m.name.empty(), "MaterialTable: material " + std::to_string(materials_.size()) + " has an empty name");
    require(index_of(m.name) < 0, "MaterialTable: material name '" + m.name + "' is used twice");
    require(size() < max_materials, "MaterialTable: more than " + std::to_string(max_materials) + " materials");
    materials_.push_back(std::move(m));
    return size() - 1;
  }

  int size() const { return static_cast<int>(materials_.size()); }
  bool empty() const { return materials_.empty(); }
  const Material& operator[](int i) const { return materials_.at(static_cast<std::size_t>(i)); }
  const std::vector<Material>& materials() const { return materials_; }

  // -1 when no material has that name.
  int index_of(const std::string& name) const {
    for (std::size_t i = 0; i < materials_.size(); ++i)
      if (materials_[i].name == name) return static_cast<int>(i);
    return -1;
  }

private:
  std::vector<Material> materials_;
};

}  // namespace trivar
