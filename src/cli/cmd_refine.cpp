// trivar refine FILE (--uniform N | --insert dir:values ...) -o OUT: h-refinement by knot insertion.
#include <string>
#include <variant>
#include <vector>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/spline/knot_insertion.hpp"

namespace trivar::cli {

namespace {

struct Insertion {
  int dir = 0;
  std::vector<double> values;
};

// "dir:value[,value...]" with dir 0/1/2 or u/v/w.
Insertion parse_insertion(const std::string& spec) {
  const std::string what = "refine: --insert '" + spec + "': ";
  const auto colon = spec.find(':');
  require(colon != std::string::npos && colon + 1 < spec.size(), what + "expected dir:value[,value...]");
  const std::string dir = spec.substr(0, colon);
  Insertion ins;
  if (dir == "u" || dir == "0") ins.dir = 0;
  else if (dir == "v" || dir == "1") ins.dir = 1;
  else if (dir == "w" || dir == "2") ins.dir = 2;
  else throw Error(what + "direction must be u, v, w or 0, 1, 2");
  std::size_t pos = colon + 1;
  while (pos <= spec.size()) {
    const std::size_t end = std::min(spec.find(',', pos), spec.size());
    const std::string item = spec.substr(pos, end - pos);
    std::size_t used = 0;
    double x = 0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    require(!item.empty() && used == item.size(), what + "'" + item + "' is not a number");
    ins.values.push_back(x);
    pos = end + 1;
  }
  return ins;
}

template <int D>
TensorSpline<D> refine(TensorSpline<D> s, int uniform, const std::vector<Insertion>& insertions) {
  for (const Insertion& ins : insertions) {
    require(ins.dir < D, "refine: direction " + std::to_string(ins.dir) + " does not exist in a " + kind_name(D));
    const Box<D> dom = s.domain();
    for (double x : ins.values)
      require(x > dom.lo[ins.dir] && x < dom.hi[ins.dir], "refine: knot " + fmt(x) + " in direction " +
                                                              std::to_string(ins.dir) + " is not inside the domain (" +
                                                              fmt(dom.lo[ins.dir]) + ", " + fmt(dom.hi[ins.dir]) + ")");
    s = insert_knots(s, ins.dir, ins.values);
  }
  if (uniform > 1) {
    Ints<D> n;
    n.fill(uniform);
    s = refine_uniform(s, n);
  }
  return s;
}

}  // namespace

void add_refine_command(CLI::App& app, Context&) {
  auto* cmd = app.add_subcommand("refine", "Refine by knot insertion (geometry unchanged)");
  struct Args {
    std::string in, out;
    int uniform = 1;
    std::vector<std::string> insert;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("FILE", a->in, "Input spline file (.json, .g2)")->required();
  cmd->add_option("-o,--output", a->out, "Output spline file (.json, .g2)")->required();
  auto* uniform = cmd->add_option("--uniform", a->uniform, "Split every element into N equal parts in every direction")
                      ->check(at_least(1));
  auto* insert = cmd->add_option("--insert", a->insert,
                                 "Insert knots: dir:value[,value...] with dir u, v, w (or 0, 1, 2); repeatable; "
                                 "applied before --uniform")
                     ->take_all();
  cmd->callback([a, uniform, insert] {
    require(uniform->count() + insert->count() > 0, "refine: give --uniform N and/or --insert dir:values");
    std::vector<Insertion> insertions;
    for (const std::string& spec : a->insert) insertions.push_back(parse_insertion(spec));
    std::vector<AnySpline> objects = read_objects(a->in);
    for (AnySpline& o : objects)
      o = std::visit([&](const auto& s) { return AnySpline(refine(s, a->uniform, insertions)); }, o);
    io::write_spline_file(a->out, objects);
  });
}

}  // namespace trivar::cli
