// trivar refine FILE (--uniform N | --insert dir:values ...) -o OUT: h-refinement by knot insertion;
// trivar refine FILE --strategy S [selection] [--levels L] [--report] -o OUT: local refinement as an LR spline.
#include <chrono>
#include <cstdio>
#include <numeric>
#include <string>
#include <variant>
#include <vector>

#include "cli.hpp"
#include "lr_cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/lr/refinement.hpp"
#include "trivar/lr/selection.hpp"
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

// What one level of LR refinement acts on; at most one of the lists is non-empty, none means every element.
struct Selection {
  std::vector<int> elements, functions;
  std::vector<double> box, segment;  // lo then hi, P0 then P1: 2 D values each
};

template <int D>
void split_points(const std::vector<double>& v, const char* option, Param<D>& a, Param<D>& b) {
  require(static_cast<int>(v.size()) == 2 * D, std::string("refine: ") + option + " takes " + std::to_string(2 * D) +
                                                   " values for an LR " + kind_name(D) + " (" + std::to_string(D) +
                                                   " per point), got " + std::to_string(v.size()));
  for (int k = 0; k < D; ++k) {
    a[k] = v[static_cast<std::size_t>(k)];
    b[k] = v[static_cast<std::size_t>(k + D)];
  }
}

// One level: the selection evaluated on the current mesh, then one batch of rectangles; returns how many
// elements or B-splines were selected (the literature's "refined" count). Box and segment select elements for
// FULLSPAN / MINSPAN and B-splines for STRUCTURED, the objects those strategies act on.
template <int D>
int refine_level(LRSpline<D>& lr, const Selection& sel, const RefineOptions& opts) {
  const bool structured = opts.strategy == Strategy::structured;
  auto refine = [&](const std::vector<int>& ids, bool functions) {
    if (functions)
      refine_functions(lr, ids, opts);
    else
      refine_elements(lr, ids, opts);
    return static_cast<int>(ids.size());
  };
  if (!sel.elements.empty())
    return refine(checked_ids(sel.elements, lr.num_elements(), "refine: --elements: element"), false);
  if (!sel.functions.empty())
    return refine(checked_ids(sel.functions, lr.num_basis(), "refine: --functions: B-spline"), true);
  // A box or segment that misses every element's interior is a mistake, not a request to change nothing.
  auto nonempty = [&](std::vector<int> ids, const char* option) {
    require(!ids.empty(), std::string("refine: ") + option + " meets the interior of no " +
                              (structured ? "B-spline support" : "element"));
    return ids;
  };
  Param<D> a{}, b{};
  if (!sel.box.empty()) {
    split_points<D>(sel.box, "--box", a, b);
    for (int k = 0; k < D; ++k)
      require(a[k] <= b[k], "refine: --box: lo " + fmt(a[k]) + " > hi " + fmt(b[k]) + " in direction " + std::to_string(k));
    const Box<D> q{a, b};
    return refine(nonempty(structured ? functions_in_box(lr, q) : elements_in_box(lr, q), "--box"), structured);
  }
  if (!sel.segment.empty()) {
    split_points<D>(sel.segment, "--segment", a, b);
    return refine(nonempty(structured ? functions_on_segment(lr, a, b) : elements_on_segment(lr, a, b), "--segment"),
                  structured);
  }
  std::vector<int> all(static_cast<std::size_t>(lr.num_elements()));
  std::iota(all.begin(), all.end(), 0);
  return refine(all, false);
}

template <int D>
void refine_lr(LRSpline<D>& lr, const Selection& sel, const RefineOptions& opts, int levels, bool report) {
  for (int k = 0; k < D; ++k)
    require(opts.multiplicity <= lr.degree(k) + 1, "refine: --multiplicity " + std::to_string(opts.multiplicity) +
                                                       " exceeds degree + 1 = " + std::to_string(lr.degree(k) + 1) +
                                                       " in direction " + std::to_string(k));
  for (int level = 1; level <= levels; ++level) {
    const auto start = std::chrono::steady_clock::now();
    const int refined = refine_level(lr, sel, opts);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (report)
      std::printf("level %d: refined %d, basis %d, elements %d, meshrects %zu, seconds %.6f\n", level, refined,
                  lr.num_basis(), lr.num_elements(), lr.mesh().size(), seconds);
  }
}

}  // namespace

void add_refine_command(CLI::App& app, Context&) {
  auto* cmd = app.add_subcommand("refine", "Refine by knot insertion (geometry unchanged)");
  struct Args {
    std::string in, out;
    int uniform = 1;
    std::vector<std::string> insert;
    std::string strategy;
    RefineOptions opts;
    Selection sel;
    int levels = 1;
    bool report = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("FILE", a->in, "Input spline file (.json, .g2), or LR spline file (.lr, .g2, .json)")->required();
  cmd->add_option("-o,--output", a->out, "Output spline file (.json, .g2); with --strategy an LR file (.lr, .g2, .json, .vtu)")
      ->required();
  auto* uniform = cmd->add_option("--uniform", a->uniform, "Split every element into N equal parts in every direction")
                      ->check(at_least(1));
  auto* insert = cmd->add_option("--insert", a->insert,
                                 "Insert knots: dir:value[,value...] with dir u, v, w (or 0, 1, 2); repeatable; "
                                 "applied before --uniform")
                     ->take_all();
  // LR refinement; the options below need --strategy.
  auto* strategy = cmd->add_option("--strategy", a->strategy,
                                   "Local refinement as an LR spline: fullspan, minspan or structured (a tensor input "
                                   "is converted exactly first)");
  std::vector<CLI::Option*> lr_options{
      cmd->add_option("--multiplicity", a->opts.multiplicity, "LR: multiplicity of the inserted mesh rectangles")
          ->check(at_least(1)),
      cmd->add_option("--max-aspect-ratio", a->opts.max_aspect_ratio,
                      "LR: cut a box only in the directions that keep its aspect ratio <= R (R >= 1)")
          ->check(at_least(1)),
      cmd->add_option("--elements", a->sel.elements, "LR: element ids to refine (--levels 1 only)")->expected(1, -1),
      cmd->add_option("--functions", a->sel.functions, "LR: B-spline ids to refine (--levels 1 only)")->expected(1, -1),
      cmd->add_option("--box", a->sel.box, "LR: refine what meets the open interior of the parameter box lo.. hi..")
          ->expected(1, 6),
      cmd->add_option("--segment", a->sel.segment, "LR: refine what meets the segment P0.. P1.. in parameter space")
          ->expected(1, 6),
      cmd->add_option("--levels", a->levels, "LR: repeat selection and refinement L times")->check(at_least(1)),
      cmd->add_flag("--report", a->report,
                    "LR: print per level 'level L: refined K, basis N, elements E, meshrects M, seconds T'")};
  cmd->callback([a, uniform, insert, strategy, lr_options] {
    if (strategy->count() > 0) {
      require(uniform->count() + insert->count() == 0, "refine: --uniform and --insert do not combine with --strategy");
      try {
        a->opts.strategy = parse_strategy(a->strategy);
      } catch (const Error& e) {
        throw Error(std::string("refine: --strategy: ") + e.what());
      }
      const int selections = !a->sel.elements.empty() + !a->sel.functions.empty() + !a->sel.box.empty() +
                             !a->sel.segment.empty();
      require(selections <= 1, "refine: give at most one of --elements, --functions, --box, --segment");
      require(a->levels == 1 || (a->sel.elements.empty() && a->sel.functions.empty()),
              "refine: --elements and --functions name ids of the input mesh; with --levels > 1 select by --box or "
              "--segment");
      require(lr_output_extension(a->out), "refine: cannot write LR splines to '" + a->out + "' (use .lr, .g2, .json or .vtu)");
      std::vector<AnyLRSpline> objects = read_as_lr(a->in, "refine");
      require(objects.size() == 1, "refine: --strategy takes a file with exactly one object; " + a->in + " holds " +
                                       std::to_string(objects.size()));
      std::visit([&](auto& lr) { refine_lr(lr, a->sel, a->opts, a->levels, a->report); }, objects.front());
      write_lr_file(a->out, objects, "refine");
      return;
    }
    for (const CLI::Option* o : lr_options)
      require(o->count() == 0, "refine: " + o->get_name() + " needs --strategy");
    if (const auto lr = read_lr_if_any(a->in); lr)
      throw Error("refine: " + a->in + " holds LR splines; give --strategy fullspan|minspan|structured");
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
