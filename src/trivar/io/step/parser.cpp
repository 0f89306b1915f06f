#include "trivar/io/step/parser.hpp"

#include <fstream>
#include <iterator>

#include "trivar/core/error.hpp"
#include "trivar/io/step/lexer.hpp"
#include "trivar/io/step/reference_cycles.hpp"

namespace trivar::io::step {

namespace {

// Deeper nesting than any schema uses; the limit keeps hostile input from exhausting the stack.
constexpr int max_nesting = 64;

class Parser {
public:
  Parser(Lexer& lexer, const ReadOptions& options)
      : lex_(lexer), options_(options), warnings_(options.strict), scratch_(max_nesting + 2) {
    lex_.set_warnings(&warnings_);
  }

  ExchangeFile run() {
    advance();
    expect_keyword("ISO-10303-21");
    expect(TokenKind::semicolon);
    expect_keyword("HEADER");
    expect(TokenKind::semicolon);
    header_section();
    bool data = false;
    while (true) {
      if (tok_.kind != TokenKind::keyword) unexpected("DATA, ENDSEC-terminated section or END-ISO-10303-21");
      const Token start = tok_;
      if (tok_.text == "END-ISO-10303-21") {
        advance();
        if (tok_.kind != TokenKind::semicolon) unexpected("';'");
        break;  // anything after the end marker is not part of the exchange structure
      }
      if (tok_.text == "DATA") {
        advance();
        data_section();
        data = true;
      } else if (tok_.text == "ANCHOR" || tok_.text == "REFERENCE" || tok_.text == "SIGNATURE") {
        lex_.skip_section(start.line, start.column);
        advance();
      } else {
        unexpected("DATA, ANCHOR, REFERENCE, SIGNATURE or END-ISO-10303-21");
      }
    }
    if (!data) lex_.fail(tok_.line, tok_.column, "no DATA section");
    if (options_.check_references) {
      file_.check_references(lex_.name(), &warnings_);
      if (const std::vector<std::uint64_t> cycle = find_reference_cycle(file_, referring_); !cycle.empty())
        warnings_.note(Departure::reference_cycle, [&] { return cycle_message(cycle); });
    }
    file_.sort_points();
    file_.warnings = warnings_.take();
    return std::move(file_);
  }

private:
  void advance() { lex_.next(tok_); }

  // "file: #3: reference cycle #3 -> #5 -> #3 (ADVANCED_FACE -> FACE_BOUND -> ADVANCED_FACE)".
  std::string cycle_message(const std::vector<std::uint64_t>& cycle) const {
    std::string ids, types;
    for (const std::uint64_t id : cycle) {
      ids += (ids.empty() ? "#" : " -> #") + std::to_string(id);
      std::string type = "?";
      if (const Instance* i = file_.find(id)) type = i->type_name();
      for (const ExchangeFile::Skipped& sk : file_.skipped_instances())
        if (sk.id == id) type = *sk.type_name;
      types += (types.empty() ? "" : " -> ") + type;
    }
    return lex_.name() + ": #" + std::to_string(cycle.front()) + ": reference cycle " + ids + " (" + types + ")";
  }

  [[noreturn]] void unexpected(const std::string& wanted) {
    std::string found = token_name(tok_.kind);
    if (tok_.kind == TokenKind::keyword) found += " (" + tok_.text + ")";
    lex_.fail(tok_.line, tok_.column, "expected " + wanted + ", found " + found);
  }
  void expect(TokenKind kind) {
    if (tok_.kind != kind) unexpected(token_name(kind));
    advance();
  }
  void expect_keyword(const char* keyword) {
    if (tok_.kind != TokenKind::keyword || tok_.text != keyword) unexpected(keyword);
    advance();
  }

  void header_section() {
    while (!(tok_.kind == TokenKind::keyword && tok_.text == "ENDSEC")) {
      if (tok_.kind != TokenKind::keyword) unexpected("a header entity or ENDSEC");
      const Token start = tok_;
      Record r;
      r.keyword = tok_.text;
      advance();
      parameter_list(r.params);
      expect(TokenKind::semicolon);
      header_entity(std::move(r), start);
    }
    advance();
    expect(TokenKind::semicolon);
  }

  void header_entity(Record r, const Token& at) {
    auto text = [&](std::size_t k, const char* what) -> std::string {
      if (k >= r.params.size() || r.params[k].kind() == Kind::unset) return {};
      if (const auto* s = r.params[k].get_if<std::string>()) return *s;
      lex_.fail(at.line, at.column, r.keyword + ": " + what + " must be a string");
    };
    auto texts = [&](std::size_t k, const char* what) -> std::vector<std::string> {
      std::vector<std::string> out;
      if (k >= r.params.size() || r.params[k].kind() == Kind::unset) return out;
      const auto* l = r.params[k].get_if<List>();
      if (!l) lex_.fail(at.line, at.column, r.keyword + ": " + what + " must be a list of strings");
      for (const Parameter& p : l->items) {
        const auto* s = p.get_if<std::string>();
        if (!s) lex_.fail(at.line, at.column, r.keyword + ": " + what + " must be a list of strings");
        out.push_back(*s);
      }
      return out;
    };
    Header& h = file_.header;
    if (r.keyword == "FILE_DESCRIPTION") {
      h.description = texts(0, "description");
      h.implementation_level = text(1, "implementation_level");
    } else if (r.keyword == "FILE_NAME") {
      h.name = text(0, "name");
      h.time_stamp = text(1, "time_stamp");
      h.author = texts(2, "author");
      h.organization = texts(3, "organization");
      h.preprocessor_version = text(4, "preprocessor_version");
      h.originating_system = text(5, "originating_system");
      h.authorization = text(6, "authorization");
    } else if (r.keyword == "FILE_SCHEMA") {
      h.schemas = texts(0, "schema_identifiers");
    } else {
      h.extra.push_back(std::move(r));
    }
  }

  void data_section() {
    if (tok_.kind == TokenKind::open) {  // edition 3: DATA('name', ('schema'));
      std::vector<Parameter> ignored;
      parameter_list(ignored);
    }
    expect(TokenKind::semicolon);
    while (tok_.kind == TokenKind::instance_name) instance();
    if (tok_.kind != TokenKind::keyword || tok_.text != "ENDSEC") unexpected("an instance or ENDSEC");
    advance();
    expect(TokenKind::semicolon);
  }

  [[noreturn]] void duplicate(const Token& at, std::uint64_t id) {
    const Instance* first = file_.find(id);
    lex_.fail(at.line, at.column,
              "duplicate instance id" + (first ? " (first defined at line " + std::to_string(first->line) + ")" : std::string()));
  }

  void instance() {
    const Token start = tok_;
    const std::uint64_t id = tok_.id;
    lex_.set_instance(id);
    if (file_.defines(id)) duplicate(start, id);
    advance();
    expect(TokenKind::equals);
    Instance inst{id, {}, false, start.line, start.column};
    refers_ = false;
    if (tok_.kind == TokenKind::keyword) {
      if (options_.keep && !options_.keep(tok_.text)) {
        skipped_references_.clear();
        lex_.skip_past_semicolon(start.line, start.column, skipped_references_);
        file_.note_skipped(id, tok_.text, start.line, start.column, skipped_references_);
        if (!skipped_references_.empty()) referring_.push_back(id);
        lex_.set_instance(0);
        advance();
        return;
      }
      inst.records.push_back(record());
    } else if (tok_.kind == TokenKind::open) {
      inst.complex = true;
      advance();
      while (tok_.kind == TokenKind::keyword) inst.records.push_back(record());
      if (inst.records.empty()) unexpected("a partial record");
      expect(TokenKind::close);
    } else {
      unexpected("an entity keyword or '('");
    }
    if (tok_.kind != TokenKind::semicolon) unexpected("';'");
    bool kept = !options_.keep;
    for (std::size_t k = 0; k < inst.records.size() && !kept; ++k) kept = options_.keep(inst.records[k].keyword);
    if (refers_) referring_.push_back(id);
    if (kept) {
      if (!(options_.compact_points && insert_compact_point(inst))) file_.insert(std::move(inst));
    } else {
      skipped_references_.clear();
      for (const Record& r : inst.records)
        for (const Parameter& p : r.params) collect_references(p, skipped_references_);
      file_.note_skipped(id, inst.type_name(), start.line, start.column, skipped_references_);
    }
    lex_.set_instance(0);
    advance();
  }

  // CARTESIAN_POINT('', (x[, y[, z]])) into the compact point table; false for any other instance.
  bool insert_compact_point(const Instance& inst) {
    if (inst.complex || inst.records.front().keyword != "CARTESIAN_POINT") return false;
    const std::vector<Parameter>& params = inst.records.front().params;
    const auto* name = params.size() == 2 ? params[0].get_if<std::string>() : nullptr;
    const auto* coordinates = params.size() == 2 ? params[1].get_if<List>() : nullptr;
    if (!name || !name->empty() || !coordinates || coordinates->items.empty() || coordinates->items.size() > 3) return false;
    ExchangeFile::Point p{inst.id, {}, static_cast<int>(coordinates->items.size())};
    for (std::size_t k = 0; k < coordinates->items.size(); ++k) {
      const auto x = coordinates->items[k].number();
      if (!x) return false;
      p.coordinates[k] = *x;
    }
    file_.insert_point(p);
    return true;
  }

  Record record() {
    Record r;
    r.keyword = std::move(tok_.text);
    advance();
    parameter_list(r.params);
    return r;
  }

  // '(' [parameter {',' parameter}] ')'
  void parameter_list(std::vector<Parameter>& out, int depth = 0) {
    expect(TokenKind::open);
    if (tok_.kind == TokenKind::close) {
      advance();
      return;
    }
    // Collected in a reused vector per depth and moved out at the exact size: one allocation per list.
    std::vector<Parameter>& s = scratch_[static_cast<std::size_t>(depth)];
    s.clear();
    while (true) {
      s.push_back(parameter(depth));
      if (tok_.kind == TokenKind::close) break;
      if (tok_.kind != TokenKind::comma) unexpected("',' or ')'");
      advance();
    }
    advance();
    out.assign(std::make_move_iterator(s.begin()), std::make_move_iterator(s.end()));
  }

  Parameter parameter(int depth) {
    if (depth > max_nesting) lex_.fail(tok_.line, tok_.column, "parameters nested deeper than " + std::to_string(max_nesting));
    Parameter p;
    switch (tok_.kind) {
      case TokenKind::dollar: p = Unset{}; break;
      case TokenKind::star: p = Derived{}; break;
      case TokenKind::integer: p = tok_.integer; break;
      case TokenKind::real: p = tok_.real; break;
      case TokenKind::string: p = std::move(tok_.text); break;
      case TokenKind::enumeration: p = Enumeration{std::move(tok_.text)}; break;
      case TokenKind::binary: p = Binary{std::move(tok_.text)}; break;
      case TokenKind::instance_name:
        p = Reference{tok_.id};
        refers_ = true;
        break;
      case TokenKind::open: {
        List l;
        parameter_list(l.items, depth + 1);
        return l;
      }
      case TokenKind::keyword: {
        Typed t{std::move(tok_.text), {}};
        advance();
        expect(TokenKind::open);
        t.boxed.push_back(parameter(depth + 1));
        if (tok_.kind != TokenKind::close) unexpected("')' closing the typed parameter " + t.keyword);
        advance();
        return t;
      }
      default: unexpected("a parameter");
    }
    advance();
    return p;
  }

  Lexer& lex_;
  const ReadOptions& options_;
  Token tok_;
  ReadWarnings warnings_;
  ExchangeFile file_;
  std::vector<std::vector<Parameter>> scratch_;
  std::vector<std::uint64_t> skipped_references_;
  // Instances that refer to others, in file order: the only possible members of a reference cycle, found
  // while parsing so the cycle search need not walk the whole store again.
  std::vector<std::uint64_t> referring_;
  bool refers_ = false;  // the instance being parsed holds a reference
};

}  // namespace

ExchangeFile read_exchange_file(std::istream& in, const std::string& name, const ReadOptions& options) {
  Lexer lexer(in, name, options.chunk_size);
  return Parser(lexer, options).run();
}

ExchangeFile read_exchange_file(const std::string& path, const ReadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  require(static_cast<bool>(in), [&] { return path + ": cannot open for reading"; });
  return read_exchange_file(in, path, options);
}

ExchangeFile parse_exchange_file(std::string_view text, const std::string& name, const ReadOptions& options) {
  Lexer lexer(text, name);
  return Parser(lexer, options).run();
}

}  // namespace trivar::io::step
