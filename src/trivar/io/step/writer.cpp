#include "trivar/io/step/writer.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <unordered_map>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/step/real_format.hpp"
#include "trivar/io/step/string_codec.hpp"

namespace trivar::io::step {

namespace {

bool is_keyword(const std::string& k) {
  std::size_t i = k.size() > 1 && k[0] == '!' ? 1 : 0;
  if (i >= k.size() || !((k[i] >= 'A' && k[i] <= 'Z') || k[i] == '_')) return false;
  return std::all_of(k.begin() + static_cast<std::ptrdiff_t>(i), k.end(),
                     [](char c) { return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; });
}

class Emitter {
public:
  Emitter(std::ostream& os, const WriteOptions& options, const std::unordered_map<std::uint64_t, std::uint64_t>* ids)
      : os_(os), width_(options.line_width), ids_(ids) {}
  ~Emitter() = default;

  void raw(std::string_view s) {
    out_ += s;
    if (const std::size_t nl = s.rfind('\n'); nl != std::string_view::npos) line_begin_ = out_.size() - s.size() + nl + 1;
  }
  void end_statement() {
    out_ += ";\n";
    line_begin_ = out_.size();
    if (out_.size() > (1u << 16)) flush();
  }
  void flush() {
    os_.write(out_.data(), static_cast<std::streamsize>(out_.size()));
    out_.clear();
    line_begin_ = 0;
  }
  void id(std::uint64_t id) {
    out_ += '#';
    out_ += std::to_string(map(id));
  }
  void string(std::string_view s) {
    const std::string encoded = encode_string(s);
    // Strings are never split, so a long one starts a fresh line instead.
    if (out_.size() - line_begin_ + encoded.size() > width_ && out_.size() - line_begin_ > 8) {
      out_ += "\n  ";
      line_begin_ = out_.size() - 2;
    }
    out_ += '\'';
    out_ += encoded;
    out_ += '\'';
  }
  void strings(const std::vector<std::string>& list) {
    out_ += '(';
    for (std::size_t k = 0; k < list.size(); ++k) {
      if (k) comma();
      string(list[k]);
    }
    if (list.empty()) out_ += "''";  // the header lists are LIST [1:?] OF STRING
    out_ += ')';
  }
  void comma() {
    out_ += ',';
    if (out_.size() - line_begin_ > width_) {
      out_ += "\n  ";
      line_begin_ = out_.size() - 2;
    }
  }
  void record(const Record& r) {
    if (!is_keyword(r.keyword)) throw Error("'" + r.keyword + "' is not a P21 keyword");
    out_ += r.keyword;
    params(r.params);
  }
  void params(const std::vector<Parameter>& ps) {
    out_ += '(';
    for (std::size_t k = 0; k < ps.size(); ++k) {
      if (k) comma();
      parameter(ps[k]);
    }
    out_ += ')';
  }
  void parameter(const Parameter& p) {
    switch (p.kind()) {
      case Kind::unset: out_ += '$'; break;
      case Kind::derived: out_ += '*'; break;
      case Kind::integer: out_ += std::to_string(*p.get_if<std::int64_t>()); break;
      case Kind::real: append_real(out_, *p.get_if<double>()); break;
      case Kind::string: string(*p.get_if<std::string>()); break;
      case Kind::enumeration: {
        const std::string& name = p.get_if<Enumeration>()->name;
        if (name.empty() || !std::all_of(name.begin(), name.end(), [](char c) {
              return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
            }))
          throw Error("'" + name + "' is not a P21 enumeration name");
        out_ += '.';
        out_ += name;
        out_ += '.';
        break;
      }
      case Kind::reference: id(p.get_if<Reference>()->id); break;
      case Kind::binary: {
        const std::string& hex = p.get_if<Binary>()->hex;
        if (hex.empty() || hex[0] > '3' || (hex[0] != '0' && hex.size() == 1) ||
            !std::all_of(hex.begin(), hex.end(), [](char c) { return (c >= '0' && c <= '9') || (c >= 'A' && c <= 'F'); }))
          throw Error("\"" + hex + "\" is not a P21 binary");
        out_ += '"';
        out_ += hex;
        out_ += '"';
        break;
      }
      case Kind::list: params(p.get_if<List>()->items); break;
      case Kind::typed: {
        const Typed& t = *p.get_if<Typed>();
        if (!is_keyword(t.keyword) || t.boxed.size() != 1) throw Error("malformed typed parameter '" + t.keyword + "'");
        out_ += t.keyword;
        out_ += '(';
        parameter(t.value());
        out_ += ')';
        break;
      }
    }
  }

private:
  std::uint64_t map(std::uint64_t id) const {
    if (!ids_) return id;
    const auto it = ids_->find(id);
    if (it == ids_->end()) throw Error("reference to #" + std::to_string(id) + ", which is not in the file");
    return it->second;
  }

  std::ostream& os_;
  std::size_t width_;
  const std::unordered_map<std::uint64_t, std::uint64_t>* ids_;
  std::string out_;
  std::size_t line_begin_ = 0;
};

}  // namespace

std::string iso8601_now() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&t, &utc);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &utc);
  return buf;
}

void write_exchange_file(std::ostream& os, const ExchangeFile& file, const WriteOptions& options) {
  const Header& h = file.header;
  require(!h.schemas.empty(), "FILE_SCHEMA needs at least one schema name");
  // Compact points are a reader's summary (names dropped), not instances: writing would leave references dangling.
  require(file.point_count() == 0, "cannot write a store read with compact points (ReadOptions::compact_points)");
  std::unordered_map<std::uint64_t, std::uint64_t> ids;
  if (options.renumber) {
    ids.reserve(file.size());
    std::uint64_t next = 1;
    for (const Instance& i : file.instances()) ids.emplace(i.id, next++);
  }
  Emitter e(os, options, options.renumber ? &ids : nullptr);
  e.raw("ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(");
  e.strings(h.description);
  e.raw(",'2;1');\nFILE_NAME(");
  e.string(h.name);
  e.comma();
  e.string(options.time_stamp.empty() ? iso8601_now() : options.time_stamp);
  e.comma();
  e.strings(h.author);
  e.comma();
  e.strings(h.organization);
  e.comma();
  e.string("trivar " + (options.version.empty() ? std::string(TRIVAR_VERSION) : options.version));
  e.comma();
  e.string(h.originating_system);
  e.comma();
  e.string(h.authorization);
  e.raw(");\nFILE_SCHEMA(");
  e.strings(h.schemas);
  e.raw(")");
  e.end_statement();
  for (const Record& r : h.extra) {
    e.record(r);
    e.end_statement();
  }
  e.raw("ENDSEC;\nDATA;\n");
  std::vector<const Record*> sorted;
  for (const Instance& i : file.instances()) {
    try {
      e.id(i.id);
      e.raw("=");
      if (i.complex) {
        sorted.clear();
        for (const Record& r : i.records) sorted.push_back(&r);
        std::sort(sorted.begin(), sorted.end(), [](const Record* a, const Record* b) { return a->keyword < b->keyword; });
        e.raw("(");
        for (const Record* r : sorted) e.record(*r);
        e.raw(")");
      } else {
        require(i.records.size() == 1, "a simple instance has exactly one record");
        e.record(i.records.front());
      }
      e.end_statement();
    } catch (const Error& err) {
      throw Error("#" + std::to_string(i.id) + " (" + i.type_name() + "): " + err.what());
    }
  }
  e.raw("ENDSEC;\nEND-ISO-10303-21;\n");
  e.flush();
  require(static_cast<bool>(os), "write error");
}

void write_exchange_file(const std::string& path, const ExchangeFile& file, const WriteOptions& options) {
  write_file_atomically(path, [&](std::ostream& os) {
    try {
      write_exchange_file(os, file, options);
    } catch (const Error& e) {
      throw Error(path + ": " + e.what());
    }
  });
}

}  // namespace trivar::io::step
