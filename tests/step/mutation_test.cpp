// Robustness of the P21 reader against corrupted input: every mutation of a valid file either parses or
// fails with a one-line trivar::Error; never a crash, hang or other exception. Runs under ASan/UBSan in the
// debug-asan preset as a deterministic fuzz campaign (the libFuzzer target in fuzz/ explores further).
#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "step/step_test_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/step/parser.hpp"
#include "trivar/io/step/step_file.hpp"
#include "trivar/io/step/writer.hpp"

using namespace trivar;
using namespace trivar::io::step;

namespace {

std::string mutate(std::string text, std::mt19937& rng) {
  static const std::string alphabet = "0123456789-+.E#=();,'\"$*/\\SXP!_ \nABCT.F.U";
  std::uniform_int_distribution<int> edits(1, 4), kind(0, 3), byte(0, 255);
  for (int e = edits(rng); e > 0 && !text.empty(); --e) {
    const std::size_t at = std::uniform_int_distribution<std::size_t>(0, text.size() - 1)(rng);
    const char c = kind(rng) == 3 ? static_cast<char>(byte(rng))
                                  : alphabet[std::uniform_int_distribution<std::size_t>(0, alphabet.size() - 1)(rng)];
    switch (kind(rng)) {
      case 0: text.erase(at, std::uniform_int_distribution<std::size_t>(1, 8)(rng)); break;
      case 1: text.insert(at, text.substr(at, 16)); break;
      case 2: text[at] = c; break;
      default: text.insert(text.begin() + static_cast<std::ptrdiff_t>(at), c); break;
    }
  }
  return text;
}

void campaign(const std::string& seed_file, int runs, unsigned seed) {
  const std::string text = test::slurp_file(test::step_data(seed_file));
  std::mt19937 rng(seed);
  int rejected = 0;
  for (int r = 0; r < runs; ++r) {
    const std::string m = mutate(text, rng);
    ReadOptions o;
    if (r % 3 == 1) o.keep = [](std::string_view k) { return k.size() % 2 == 0; };  // exercise the skip path
    if (r % 3 == 2) o.chunk_size = 5;                                              // and chunk boundaries
    try {
      std::istringstream in(m);
      const ExchangeFile f = r % 3 == 0 ? parse_exchange_file(m, "m.stp", o) : read_exchange_file(in, "m.stp", o);
      // What parses must also write and read back (renumbered, so only the count is compared).
      std::ostringstream out;
      WriteOptions w;
      w.time_stamp = "2026-01-01T00:00:00";
      if (!f.header.schemas.empty() && f.skipped_total() == 0) {
        write_exchange_file(out, f, w);
        EXPECT_EQ(parse_exchange_file(out.str()).size(), f.size());
      }
    } catch (const Error& e) {
      ++rejected;
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << "multi-line message: " << what;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not a trivar::Error: " << e.what();
    }
  }
  EXPECT_GT(rejected, runs / 4);
}

// The Part 42 mapping on mutated geometry files: every file maps or fails with one line, and what maps is a
// valid object (evaluated at the middle of its domain).
void geometry_campaign(const std::string& seed_file, int runs, unsigned seed) {
  const std::string text = test::slurp_file(test::step_data("geometry/" + seed_file));
  std::mt19937 rng(seed);
  int rejected = 0;
  for (int r = 0; r < runs; ++r) {
    try {
      const StepContents c = parse_step(mutate(text, rng), "m.stp");
      for (const AnySpline& s : c.splines)
        std::visit(
            [](const auto& t) {
              std::vector<double> out(static_cast<std::size_t>(t.dim()));
              t.eval(t.domain().center(), out.data());
            },
            s);
    } catch (const Error& e) {
      ++rejected;
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "multi-line message: " << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not a trivar::Error: " << e.what();
    }
  }
  EXPECT_GT(rejected, runs / 4);
}

}  // namespace

TEST(StepMutations, GeometryFilesMapOrFailCleanly) {
  unsigned seed = 2030;
  for (const char* f : {"volume_forms.stp", "lr_surface_rational.stp", "lr_volume.stp", "curve_forms.stp", "cad_part_ap214.stp"})
    geometry_campaign(f, 600, seed++);
}

TEST(StepMutations, GrammarFileFailsCleanlyOrParses) { campaign("grammar.stp", 3000, 2026); }

TEST(StepMutations, VolumeFileFailsCleanlyOrParses) { campaign("volume.stp", 3000, 2027); }
