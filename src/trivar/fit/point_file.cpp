#include "trivar/fit/point_file.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/memory_budget.hpp"

namespace trivar {
namespace {

constexpr char kMagic[8] = {'T', 'R', 'I', 'V', 'A', 'R', 'P', 'T'};
constexpr std::size_t kHeader = 24;
constexpr int kMaxColumns = 64;

template <class T>
T read_le(const char* p) {
  T v = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) v |= static_cast<T>(static_cast<unsigned char>(p[i])) << (8 * i);
  return v;
}

PointTable parse_binary(std::string_view b, const std::string& name) {
  require(b.size() >= kHeader, name + ": binary point file truncated in its 24-byte header");
  const auto cols = read_le<std::uint32_t>(b.data() + 8);
  const auto reserved = read_le<std::uint32_t>(b.data() + 12);
  const auto rows = read_le<std::uint64_t>(b.data() + 16);
  require(cols >= 1 && cols <= kMaxColumns,
          name + ": byte 8: " + std::to_string(cols) + " columns, expected 1.." + std::to_string(kMaxColumns));
  require(reserved == 0, name + ": byte 12: reserved field is " + std::to_string(reserved) + ", expected 0");
  // In integers, overflow checked first: a header may claim any 64-bit row count.
  const std::uint64_t row_bytes = 8 * std::uint64_t{cols};
  const bool representable = rows <= (UINT64_MAX - kHeader) / row_bytes;
  require(representable && kHeader + rows * row_bytes == b.size(), [&] {
    return name + ": binary point file of " + std::to_string(b.size()) + " bytes, its header (" + std::to_string(rows) +
           " rows of " + std::to_string(cols) + ") needs " +
           (representable ? std::to_string(kHeader + rows * row_bytes) : std::string("more than 2^64")) + " bytes";
  });
  PointTable t;
  t.columns = static_cast<int>(cols);
  t.values.resize(static_cast<std::size_t>(rows) * cols);
  for (std::size_t i = 0; i < t.values.size(); ++i) {
    const std::uint64_t bits = read_le<std::uint64_t>(b.data() + kHeader + 8 * i);
    double v;
    std::memcpy(&v, &bits, sizeof v);
    require(std::isfinite(v), name + ": byte " + std::to_string(kHeader + 8 * i) + " (row " +
                                  std::to_string(i / cols + 1) + "): a number that is not finite");
    t.values[i] = v;
  }
  return t;
}

bool is_separator(char c) { return c == ' ' || c == '\t' || c == ',' || c == ';' || c == '\r'; }

PointTable parse_text(std::string_view s, const std::string& name) {
  PointTable t;
  std::size_t line_no = 0, pos = 0;
  bool first_content = true;
  while (pos < s.size()) {
    std::size_t end = s.find('\n', pos);
    if (end == std::string_view::npos) end = s.size();
    std::string_view line = s.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    int count = 0;
    bool any_number = false;
    std::string_view bad;  // the first token that is not a number
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && is_separator(line[i])) ++i;
      if (i >= line.size()) break;
      std::size_t j = i;
      while (j < line.size() && !is_separator(line[j])) ++j;
      const std::string_view tok = line.substr(i, j - i);
      double v = 0.0;
      const char* b = tok.data();
      if (*b == '+') ++b;  // from_chars does not take a leading '+'
      const auto [ptr, ec] = std::from_chars(b, tok.data() + tok.size(), v);
      if (ec == std::errc() && ptr == tok.data() + tok.size()) {
        require(std::isfinite(v), name + ": line " + std::to_string(line_no) + ": '" + std::string(tok) +
                                      "' is not a finite number");
        any_number = true;
        t.values.push_back(v);
      } else if (bad.empty()) {
        bad = tok;
      }
      ++count;
      i = j;
    }
    if (count == 0) continue;
    if (first_content && !any_number) {  // a header line of column names
      first_content = false;
      continue;
    }
    first_content = false;
    if (!bad.empty()) throw Error(name + ": line " + std::to_string(line_no) + ": '" + std::string(bad) + "' is not a number");
    if (t.columns == 0) t.columns = count;
    require(count == t.columns, name + ": line " + std::to_string(line_no) + ": " + std::to_string(count) +
                                    " numbers, the rows before have " + std::to_string(t.columns));
  }
  require(t.columns > 0, name + ": no points (empty file)");
  return t;
}

}  // namespace

PointTable parse_point_bytes(std::string_view bytes, const std::string& name) {
  if (bytes.size() >= sizeof kMagic && std::memcmp(bytes.data(), kMagic, sizeof kMagic) == 0)
    return parse_binary(bytes, name);
  return parse_text(bytes, name);
}

PointTable read_point_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  require(in.good(), path + ": cannot open the point file");
  const std::streamoff size = in.tellg();
  require(size >= 0, path + ": cannot read the point file");
  // The text and the table of numbers it becomes (a number takes 8 bytes, at least 2 characters of text).
  require_memory(2.0 * static_cast<double>(size) + 4.0 * static_cast<double>(size), "reading " + path);
  require(size > 0, path + ": no points (empty file)");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  in.read(bytes.data(), size);
  require(in.good(), path + ": read error");
  return parse_point_bytes(bytes, path);
}

void write_point_file(const std::string& path, const PointTable& table) {
  require(table.columns >= 1 && table.columns <= kMaxColumns &&
              table.values.size() % static_cast<std::size_t>(table.columns) == 0,
          path + ": a point table of " + std::to_string(table.columns) + " columns and " +
              std::to_string(table.values.size()) + " numbers cannot be written");
  write_file_atomically(
      path,
      [&](std::ostream& out) {
        std::string header(kMagic, sizeof kMagic);
        auto put = [&](std::uint64_t v, int bytes) {
          for (int i = 0; i < bytes; ++i) header.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
        };
        put(static_cast<std::uint64_t>(table.columns), 4);
        put(0, 4);
        put(table.rows(), 8);
        out.write(header.data(), static_cast<std::streamsize>(header.size()));
        std::string body(8 * table.values.size(), '\0');
        for (std::size_t i = 0; i < table.values.size(); ++i) {
          std::uint64_t bits;
          std::memcpy(&bits, &table.values[i], sizeof bits);
          for (int b = 0; b < 8; ++b) body[8 * i + static_cast<std::size_t>(b)] = static_cast<char>((bits >> (8 * b)) & 0xff);
        }
        out.write(body.data(), static_cast<std::streamsize>(body.size()));
      },
      true);
}

}  // namespace trivar
