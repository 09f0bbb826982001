// metrica: one command with subcommands, like git or refine's ref.
// Exit code 0 on success, 1 on invalid input or a failed check, 2 on bad
// usage; errors are reported, never raised as a signal.
#include "cli.hpp"

#include <metrica/allocator.hpp>
#include <metrica/error.hpp>

#include <fmt/core.h>

#include <cstdio>
#include <exception>
#include <new>

namespace {

void print_usage(std::FILE* out) {
  fmt::print(out,
             "usage: metrica <command> [options]\n\n"
             "Metric-based anisotropic adaptation of tetrahedral meshes.\n\n"
             "Commands:\n");
  for (const auto& c : metrica::cli::commands()) fmt::print(out, "  {:<12} {}\n", c.name, c.summary);
  fmt::print(out, "\nRun 'metrica <command> --help' for a command's options.\n");
}

}  // namespace

int main(int argc, char** argv) {
  metrica::keep_freed_memory();  // allocator.hpp: pages reused from pass to pass
  using namespace metrica::cli;
  if (argc < 2) {
    print_usage(stderr);
    return kUsage;
  }
  const std::string name = argv[1];
  if (name == "-h" || name == "--help" || name == "help") {
    print_usage(stdout);
    return kOk;
  }
  if (name == "--version") {
    fmt::print("metrica 0.1.0\n");
    return kOk;
  }
  const std::vector<std::string> args(argv + 2, argv + argc);
  for (const auto& c : commands()) {
    if (name != c.name) continue;
    try {
      return c.run(args);
    } catch (const UsageError& e) {
      fmt::print(stderr, "error: {}\n", e.what());
      return kUsage;
    } catch (const metrica::InputError& e) {
      fmt::print(stderr, "error: {}\n", e.what());
      return kInvalid;
    } catch (const std::bad_alloc&) {
      fmt::print(stderr, "error: out of memory\n");
      return kInvalid;
    } catch (const std::exception& e) {
      fmt::print(stderr, "error: {}\n", e.what());
      return kInvalid;
    }
  }
  fmt::print(stderr, "error: unknown command '{}'\n\n", name);
  print_usage(stderr);
  return kUsage;
}
