#pragma once
// The value model of ISO 10303-21 parameters: a small closed variant that a schema mapper can walk
// without knowing the schema. Strings are held decoded (UTF-8), enumerations and keywords without their
// dots and in upper case, so comparisons in a mapper are plain string equality.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace trivar::io::step {

struct Parameter;

// `$`: an optional attribute without a value.
struct Unset {
  friend bool operator==(const Unset&, const Unset&) = default;
};
// `*`: an attribute redeclared as derived in a subtype.
struct Derived {
  friend bool operator==(const Derived&, const Derived&) = default;
};
// `.NAME.`; logicals and booleans are the enumerations T, F and U.
struct Enumeration {
  std::string name;
  friend bool operator==(const Enumeration&, const Enumeration&) = default;
};
// `#n`: a reference to the instance with id n.
struct Reference {
  std::uint64_t id = 0;
  friend bool operator==(const Reference&, const Reference&) = default;
};
// `"0FF"`: the hex digits as written (upper case); the first digit is the number of unused leading bits.
struct Binary {
  std::string hex;
  friend bool operator==(const Binary&, const Binary&) = default;
};
// `(a, b, ...)`, possibly empty or nested.
struct List {
  std::vector<Parameter> items;
  friend bool operator==(const List&, const List&) = default;
};
// `KEYWORD(value)`, e.g. PARAMETER_VALUE(0.5). The value sits in a one-element vector because the
// variant cannot hold an incomplete type by value.
struct Typed {
  std::string keyword;
  std::vector<Parameter> boxed;
  const Parameter& value() const { return boxed.front(); }
  friend bool operator==(const Typed&, const Typed&) = default;
};

enum class Kind { unset, derived, integer, real, string, enumeration, reference, binary, list, typed };

// Name of a kind for messages ("expected a list, found a real").
const char* kind_name(Kind kind);

struct Parameter {
  // Alternative order matches Kind.
  std::variant<Unset, Derived, std::int64_t, double, std::string, Enumeration, Reference, Binary, List, Typed> value;

  Parameter() = default;
  template <class T>
    requires std::is_constructible_v<decltype(value), T&&> && (!std::is_same_v<std::remove_cvref_t<T>, Parameter>)
  Parameter(T&& v) : value(std::forward<T>(v)) {}  // NOLINT: implicit on purpose, lists read naturally

  Kind kind() const { return static_cast<Kind>(value.index()); }
  template <class T>
  const T* get_if() const {
    return std::get_if<T>(&value);
  }
  // An integer or real as a double (P21 writers are not all strict about the decimal point of reals).
  std::optional<double> number() const;
  // .T. -> true, .F. -> false, anything else (including .U.) -> nullopt.
  std::optional<bool> boolean() const;
  bool is_enumeration(std::string_view name) const;

  friend bool operator==(const Parameter&, const Parameter&) = default;
};

// Helpers for building parameters in writers and tests.
inline Parameter enumeration(std::string name) { return Enumeration{std::move(name)}; }
inline Parameter reference(std::uint64_t id) { return Reference{id}; }
inline Parameter typed(std::string keyword, Parameter value) {
  Typed t{std::move(keyword), {}};
  t.boxed.push_back(std::move(value));
  return t;
}
inline Parameter list(std::vector<Parameter> items) { return List{std::move(items)}; }

}  // namespace trivar::io::step
