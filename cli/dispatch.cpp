// The command line to an exit code: the command runs inside an OutputSet,
// so its outputs replace their targets together and only on success.
#include "cli.hpp"

#include <metrica/error.hpp>
#include <metrica/io/output_set.hpp>

#include <fmt/core.h>

#include <cstdio>
#include <exception>
#include <new>

namespace metrica::cli {

namespace {

void print_usage(std::FILE* out) {
  fmt::print(out,
             "usage: metrica <command> [options]\n\n"
             "Metric-based anisotropic adaptation of tetrahedral meshes.\n\n"
             "Commands:\n");
  for (const auto& c : commands()) fmt::print(out, "  {:<12} {}\n", c.name, c.summary);
  fmt::print(out,
             "\nRun 'metrica <command> --help' for a command's options.\n"
             "Any output FILE may be '-' (or /dev/stdout): standard output, written when the run succeeded,\n"
             "as text (a mesh as ASCII .mesh, --vtu as VTU, a metric or field as ASCII .sol, a report as\n"
             "CSV); what the command prints then goes to standard error. One output at most.\n"
             "Exit status: 0 success, 1 invalid input or failed run, 2 bad usage.\n"
             "Threads: all cores unless --threads or OMP_NUM_THREADS says, fewer while other processes keep\n"
             "cores busy (looked at before each stage); waiting threads sleep at once (OMP_WAIT_POLICY=passive\n"
             "unless the environment sets it: a busy machine loses less).\n");
}

int g_rank = 0;

// Under mpirun every rank meets the same bad option or input: rank 0 says
// it. Any other error may be one rank's own: it says it with its number.
int fail(int code, const char* what, bool same_on_every_rank = true) {
  std::fflush(stdout);
  if (g_rank != 0) {
    if (!same_on_every_rank) fmt::print(stderr, "error: rank {}: {}\n", g_rank, what);
    return code;
  }
  fmt::print(stderr, "error: {}\n", what);
  return code;
}

}  // namespace

void set_process_rank(int rank) { g_rank = rank; }

int run_command_line(const std::vector<std::string>& args) {
  if (args.empty()) {
    print_usage(stderr);
    return kUsage;
  }
  const std::string& name = args[0];
  if (name == "-h" || name == "--help" || name == "help") {
    print_usage(stdout);
    return kOk;
  }
  if (name == "--version") {
    fmt::print("metrica {}\n", METRICA_VERSION);
    return kOk;
  }
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  for (const auto& c : commands()) {
    if (name != c.name) continue;
    try {
      io::OutputSet outputs;
      const int code = c.run(rest);
      if (code == kOk) outputs.commit();
      return code;
    } catch (const AlreadyReported&) {
      return kInvalid;
    } catch (const UsageError& e) {
      return fail(kUsage, e.what());
    } catch (const InputError& e) {
      return fail(kInvalid, e.what());
    } catch (const std::bad_alloc&) {
      return fail(kInvalid, "out of memory", false);
    } catch (const std::exception& e) {
      return fail(kInvalid, e.what(), false);
    }
  }
  fmt::print(stderr, "error: unknown command '{}'\n\n", name);
  print_usage(stderr);
  return kUsage;
}

}  // namespace metrica::cli
