// trivar refine FILE (--uniform N | --insert dir:values ...) -o OUT: h-refinement by knot insertion;
// trivar refine FILE --strategy S [selection] [--levels L] [--report] -o OUT: local refinement as an LR spline.
// trivar refine FILE (--rectangle ... | --rectangles FILE) -o OUT: insertion of given LR mesh rectangles.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "cli.hpp"
#include "lr_cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/memory_budget.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/lr/memory_estimate.hpp"
#include "trivar/lr/refinement.hpp"
#include "trivar/lr/selection.hpp"
#include "trivar/spline/knot_insertion.hpp"

namespace trivar::cli {

namespace {

struct Insertion {
  int dir = 0;
  std::vector<double> values;
};

// u/v/w or 0/1/2; what prefixes the error.
int parse_direction(const std::string& dir, const std::string& what) {
  if (dir == "u" || dir == "0") return 0;
  if (dir == "v" || dir == "1") return 1;
  if (dir == "w" || dir == "2") return 2;
  throw Error(what + "direction '" + dir + "' must be u, v, w or 0, 1, 2");
}

double parse_number(const std::string& item, const std::string& what) {
  std::size_t used = 0;
  double x = 0;
  try {
    x = std::stod(item, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  require(!item.empty() && used == item.size() && std::isfinite(x), what + "'" + item + "' is not a number");
  return x;
}

// "dir:value[,value...]" with dir 0/1/2 or u/v/w.
Insertion parse_insertion(const std::string& spec) {
  const std::string what = "refine: --insert '" + spec + "': ";
  const auto colon = spec.find(':');
  require(colon != std::string::npos && colon + 1 < spec.size(), what + "expected dir:value[,value...]");
  Insertion ins;
  ins.dir = parse_direction(spec.substr(0, colon), what);
  std::size_t pos = colon + 1;
  while (pos <= spec.size()) {
    const std::size_t end = std::min(spec.find(',', pos), spec.size());
    ins.values.push_back(parse_number(spec.substr(pos, end - pos), what));
    pos = end + 1;
  }
  return ins;
}

// A mesh rectangle as the fields "dir value start stop mult" (surfaces: the line u = value or v = value from
// start to stop in the other direction) or "dir value start1 stop1 start2 stop2 mult" (volumes: the plane piece
// at value in direction dir, spanning [start1, stop1] x [start2, stop2] in the other two directions in the order
// u, v, w). The LRSpline checks the values against the domain and the mesh when the rectangle is inserted.
template <int D>
MeshRectangle<D> parse_rectangle(const std::vector<std::string>& f, const std::string& what) {
  require(static_cast<int>(f.size()) == 2 * D + 1,
          what + "a mesh rectangle of an LR " + kind_name(D) + " takes " + std::to_string(2 * D + 1) + " values (" +
              (D == 2 ? "dir value start stop mult" : "dir value start1 stop1 start2 stop2 mult") + "), got " +
              std::to_string(f.size()));
  const int dir = parse_direction(f[0], what);
  require(dir < D, what + "direction " + f[0] + " does not exist in an LR " + kind_name(D));
  Param<D> lo{}, hi{};
  std::size_t i = 2;
  for (int k = 0; k < D; ++k) {
    if (k == dir) continue;
    lo[k] = parse_number(f[i++], what);
    hi[k] = parse_number(f[i++], what);
    require(lo[k] < hi[k], what + "start " + f[i - 2] + " is not below stop " + f[i - 1]);
  }
  const double m = parse_number(f[i], what);
  require(m >= 1 && m <= 64 && m == std::floor(m), what + "multiplicity '" + f[i] + "' is not a positive integer");
  return MeshRectangle<D>::make(dir, parse_number(f[1], what), lo, hi, static_cast<int>(m));
}

// The rectangles of the --rectangle options, then those of the --rectangles files (one per line, the fields of
// --rectangle separated by white space; '#' starts a comment).
template <int D>
std::vector<MeshRectangle<D>> requested_rectangles(const std::vector<std::vector<std::string>>& options,
                                                   const std::vector<std::string>& files) {
  std::vector<MeshRectangle<D>> out;
  for (std::size_t i = 0; i < options.size(); ++i)
    out.push_back(parse_rectangle<D>(options[i], "refine: --rectangle " + std::to_string(i + 1) + ": "));
  for (const std::string& path : files) {
    std::ifstream in(path);
    require(in.good(), "refine: --rectangles: cannot open " + path);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      line = line.substr(0, line.find('#'));
      std::istringstream fields(line);
      std::vector<std::string> f;
      for (std::string w; fields >> w;) f.push_back(w);
      if (!f.empty()) out.push_back(parse_rectangle<D>(f, "refine: " + path + ":" + std::to_string(number) + ": "));
    }
  }
  return out;
}

// Inserts the rectangles in order; each must change the spline (a rectangle already in the mesh, or one that
// splits no B-spline support, is a mistake in an explicit request).
template <int D>
void insert_rectangles(LRSpline<D>& lr, const std::vector<MeshRectangle<D>>& rects) {
  const int changed = lr.insert(std::span<const MeshRectangle<D>>(rects));
  require(changed == static_cast<int>(rects.size()),
          "refine: " + std::to_string(rects.size() - static_cast<std::size_t>(changed)) + " of the " +
              std::to_string(rects.size()) +
              " mesh rectangles changed nothing (already in the mesh, or splitting no B-spline support)");
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

// Refuses a level whose result would not fit in memory, before it runs. The growth of a level is estimated as
// that of the level before (the first: 2^D, every element halved in every direction, the most a level of
// FULLSPAN on a uniform mesh makes); without a selection every level refines everything, so the whole request
// is estimated up front.
template <int D>
void require_level_memory(const LRSpline<D>& lr, int level, int levels, double growth, bool everything) {
  const double steps = everything ? levels - level + 1 : 1;
  const double factor = std::pow(growth, steps);
  const double elements = lr.num_elements() * factor, basis = lr.num_basis() * factor;
  const auto approx = [](double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", x);
    return std::string(text);
  };
  const std::string size = std::isfinite(basis)
                               ? "about " + approx(elements) + " elements and " + approx(basis) + " B-splines"
                               : "more elements than a double can count";
  require_memory(lr_spline_bytes<D>(lr.degrees(), lr.stride(), basis, elements),
                 "refine --levels " + std::to_string(levels) + ": level " +
                     std::to_string(everything ? levels : level) + " (" + size + ", " + approx(growth) +
                     " times as many per level)");
}

template <int D>
void refine_lr(LRSpline<D>& lr, const Selection& sel, const RefineOptions& opts, int levels, bool report) {
  for (int k = 0; k < D; ++k)
    require(opts.multiplicity <= lr.degree(k) + 1, "refine: --multiplicity " + std::to_string(opts.multiplicity) +
                                                       " exceeds degree + 1 = " + std::to_string(lr.degree(k) + 1) +
                                                       " in direction " + std::to_string(k));
  const bool everything = sel.elements.empty() && sel.functions.empty() && sel.box.empty() && sel.segment.empty();
  double growth = 1 << D;
  if (everything) require_level_memory(lr, 1, levels, growth, true);
  for (int level = 1; level <= levels; ++level) {
    require_level_memory(lr, level, levels, growth, false);
    const double before = std::max(lr.num_elements(), lr.num_basis());
    const auto start = std::chrono::steady_clock::now();
    const int refined = refine_level(lr, sel, opts);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    growth = std::max(1.0, std::max(lr.num_elements(), lr.num_basis()) / before);
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
    std::vector<std::vector<std::string>> rectangles;
    std::vector<std::string> rectangle_files;
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
  // LR refinement by given mesh rectangles.
  auto* rectangle =
      cmd->add_option("--rectangle", a->rectangles,
                      "Insert a mesh rectangle into the LR spline: dir value start stop mult (surface), dir value "
                      "start1 stop1 start2 stop2 mult (volume; the other directions in the order u, v, w); repeatable")
          ->expected(5, 7)
          ->allow_extra_args(false);
  auto* rectangle_file = cmd->add_option("--rectangles", a->rectangle_files,
                                         "Insert the mesh rectangles of a file (one per line as for --rectangle, "
                                         "'#' comments); repeatable");
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
  cmd->callback([a, uniform, insert, strategy, lr_options, rectangle, rectangle_file] {
    if (rectangle->count() + rectangle_file->count() > 0) {
      require(uniform->count() + insert->count() + strategy->count() == 0,
              "refine: --rectangle and --rectangles do not combine with --uniform, --insert or --strategy");
      for (const CLI::Option* o : lr_options)
        require(o->count() == 0, "refine: " + o->get_name() + " needs --strategy");
      require(lr_output_extension(a->out), "refine: cannot write LR splines to '" + a->out + "' (use .lr, .g2, .json or .vtu)");
      std::vector<AnyLRSpline> objects = read_as_lr(a->in, "refine");
      require(objects.size() == 1, "refine: --rectangle takes a file with exactly one object; " + a->in + " holds " +
                                       std::to_string(objects.size()));
      std::visit([&]<int D>(LRSpline<D>& lr) {
        insert_rectangles(lr, requested_rectangles<D>(a->rectangles, a->rectangle_files));
      }, objects.front());
      write_lr_file(a->out, objects, "refine");
      return;
    }
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
