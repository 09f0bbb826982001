// metrica: one command with subcommands, like git or refine's ref.
// Exit code 0 on success, 1 on invalid input or a failed run or check, 2 on
// bad usage; errors are reported, never raised as a signal.
#include "cli.hpp"

#include <metrica/allocator.hpp>

int main(int argc, char** argv) {
  metrica::keep_freed_memory();  // allocator.hpp: pages reused from pass to pass
  return metrica::cli::run_command_line(std::vector<std::string>(argv + 1, argv + argc));
}
