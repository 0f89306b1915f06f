// trivar: command-line access to the library. Every failure ends as exactly one line
// "trivar: error: ..." on stderr and a non-zero exit code (see ExitCode in cli.hpp).
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <omp.h>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/interrupt_cleanup.hpp"
#include "trivar/core/out_of_memory_reserve.hpp"

namespace {

// More threads than any machine trivar runs on has cores, and far below where the OpenMP runtime fails to
// create them.
constexpr int kMaxThreads = 1024;

// Room for destructors that allocate while a std::bad_alloc unwinds (out_of_memory_reserve.hpp): enough for
// nlohmann::json to destroy an array of 16 million control points.
constexpr std::size_t kOutOfMemoryReserve = std::size_t{256} << 20;

// Messages are one line by contract; foreign exceptions (parsers, the standard library) are folded to one.
void print_error(std::string message) {
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  std::fprintf(stderr, "trivar: error: %s\n", message.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  using namespace trivar::cli;
  Context ctx;
  CLI::App app{"trivar: volumetric and locally refined spline models", "trivar"};
  app.set_version_flag("--version", std::string("trivar ") + TRIVAR_VERSION);
  app.require_subcommand(1);
  app.fallthrough();
  app.add_option("--threads", ctx.threads, "Threads for batch work (0: all available, at most 1024)")
      ->check(at_least(0))
      ->check(CLI::Validator(
          [](std::string& n) {
            return std::stod(n) <= kMaxThreads ? std::string()
                                               : "must be at most " + std::to_string(kMaxThreads) + ", got " + n;
          },
          "<= 1024"))
      ->each([](const std::string& n) {
        // Batch loops use OpenMP's default thread count when not told otherwise.
        if (const int t = std::stoi(n); t > 0) omp_set_num_threads(t);
      });

  add_info_command(app, ctx);
  add_eval_command(app, ctx);
  add_convert_command(app, ctx);
  add_refine_command(app, ctx);
  add_elevate_command(app, ctx);
  add_check_command(app, ctx);
  add_make_command(app, ctx);
  add_invert_command(app, ctx);
  add_export_command(app, ctx);
  add_slice_command(app, ctx);
  add_demo_command(app, ctx);
  add_solve_command(app, ctx);
  add_fit_command(app, ctx);
  add_stitch_command(app, ctx);
  add_boolean_command(app, ctx);

  trivar::install_interrupt_cleanup();
  trivar::install_out_of_memory_reserve(kOutOfMemoryReserve);
  // The subcommand being run, for messages that have no other context.
  const auto command = [&app] {
    std::string name;
    for (const CLI::App* node = &app; !node->get_subcommands().empty(); node = node->get_subcommands().front())
      name += (name.empty() ? "" : " ") + node->get_subcommands().front()->get_name();
    return name;
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // CLI11 reports an unknown command word only as a missing subcommand.
    CLI::App* node = &app;
    while (!node->get_subcommands().empty()) node = node->get_subcommands().front();
    const std::vector<std::string> rest = app.remaining(true);
    if (node->get_require_subcommand_min() > 0 && !rest.empty()) {
      const std::string prefix = node == &app ? "trivar" : "trivar " + node->get_name();
      print_error("unknown command '" + rest.front() + "' (see " + prefix + " --help)");
    } else {
      print_error(e.what());
    }
    return kUsage;
  } catch (const trivar::Error& e) {
    print_error(e.what());
    return kBadInput;
  } catch (const std::bad_alloc&) {
    print_error(command() + ": out of memory (the request is larger than the memory available)");
    return kBadInput;
  } catch (const std::exception& e) {
    print_error(e.what());
    return kBadInput;
  }
  return ctx.exit_code;
}
