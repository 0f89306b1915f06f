// Robustness of the readers against corrupted input: every mutation of a valid file must either read as
// valid splines or fail with trivar::Error — never crash, hang, or throw anything else. Runs under
// ASan/UBSan in the debug-asan preset, where it acts as a deterministic fuzz campaign.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>

#include "io/io_test_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/spline_file.hpp"

using namespace trivar;

namespace {

using test::slurp;

// Deletes, duplicates, replaces or inserts bytes, drawing replacements from characters that matter to the
// formats (digits, signs, separators, brackets) as well as arbitrary bytes.
std::string mutate(std::string text, std::mt19937& rng) {
  static const std::string alphabet = "0123456789-+.eE ,:[]{}\"\n\t1e308nanInfabc";
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

void fuzz(const std::string& extension, const std::vector<AnySpline>& seed_objects, int runs) {
  test::TempDir dir;
  const std::string original = dir.file("seed" + extension), mutated = dir.file("mutated" + extension);
  io::write_spline_file(original, seed_objects);
  const std::string text = slurp(original);
  std::mt19937 rng(2026);
  int rejected = 0;
  for (int r = 0; r < runs; ++r) {
    {
      std::ofstream out(mutated, std::ios::binary);
      out << mutate(text, rng);
    }
    try {
      for (const AnySpline& s : io::read_spline_file(mutated))
        std::visit([](const auto& x) { EXPECT_GT(x.num_coefs(), 0); }, s);
    } catch (const Error& e) {
      ++rejected;
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << "multi-line message: " << what;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not a trivar::Error: " << e.what();
    }
  }
  // Most mutations break a count or a number; a campaign where nothing is rejected tested nothing.
  EXPECT_GT(rejected, runs / 4);
}

}  // namespace

TEST(ReaderMutations, G2FailsCleanlyOrReadsValidSplines) { fuzz(".g2", test::random_objects(true, 7), 1500); }

TEST(ReaderMutations, JsonFailsCleanlyOrReadsValidSplines) { fuzz(".json", test::random_objects(true, 8), 1500); }
