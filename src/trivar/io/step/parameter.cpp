#include "trivar/io/step/parameter.hpp"

namespace trivar::io::step {

const char* kind_name(Kind kind) {
  switch (kind) {
    case Kind::unset: return "$";
    case Kind::derived: return "*";
    case Kind::integer: return "an integer";
    case Kind::real: return "a real";
    case Kind::string: return "a string";
    case Kind::enumeration: return "an enumeration";
    case Kind::reference: return "a reference";
    case Kind::binary: return "a binary";
    case Kind::list: return "a list";
    case Kind::typed: return "a typed parameter";
  }
  return "?";
}

std::optional<double> Parameter::number() const {
  if (const auto* r = get_if<double>()) return *r;
  if (const auto* i = get_if<std::int64_t>()) return static_cast<double>(*i);
  return std::nullopt;
}

std::optional<bool> Parameter::boolean() const {
  if (is_enumeration("T")) return true;
  if (is_enumeration("F")) return false;
  return std::nullopt;
}

bool Parameter::is_enumeration(std::string_view name) const {
  const auto* e = get_if<Enumeration>();
  return e && e->name == name;
}

}  // namespace trivar::io::step
