// libFuzzer target: command lines. The input's lines are the arguments
// (the first names the command); "@M", "@S", "@F" and "@D" in an argument
// become a small valid mesh, a metric, a scalar field and a scratch
// folder, so that the fuzzer reaches past the file checks. Each line is run
// with --dry-run -q through run_command_line, exactly as main() runs it:
// options, inputs and outputs are all checked, nothing is computed or
// written. A finding is a crash, a sanitizer report or an exit code other
// than 0, 1 or 2. CAD models (bootstrap, --geometry) are left out: they
// would fuzz gmsh, not Metrica.
#include "cli.hpp"

#include <metrica/box.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/log.hpp>
#include <metrica/metrics/analytic_metric.hpp>
#include <metrica/metrics/metric_field.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

std::string scratch;

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  using namespace metrica;
  scratch = (std::filesystem::temp_directory_path() / ("metrica-fuzz-" + std::to_string(::getpid()))).string();
  std::filesystem::create_directories(scratch);
  auto data = box_mesh_data({.nx = 1, .ny = 1, .nz = 1});
  io::write_meshb(scratch + "/m.meshb", data);
  io::write_sol(scratch + "/s.solb", metric_field_to_sol(analytic_metric_field(AnalyticMetric::linear, data.vertices)));
  io::write_sol(scratch + "/f.solb", scalar_field_to_sol(std::vector<double>(data.vertices.size(), 1.0)));
  std::atexit([] { std::filesystem::remove_all(scratch); });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 512) return 0;
  std::vector<std::string> args;
  std::string arg;
  for (std::size_t i = 0; i < size; ++i) {
    const char c = static_cast<char>(data[i]);
    if (c == '\n') {
      args.push_back(arg);
      arg.clear();
    } else if (c != '\0') {
      arg += c;
    }
  }
  args.push_back(arg);
  if (args.size() > 24) return 0;
  for (auto& a : args) {
    if (a == "bootstrap" || a.find("--geometry") != std::string::npos || a.find("--ge") == 0) return 0;
    replace_all(a, "@M", scratch + "/m.meshb");
    replace_all(a, "@S", scratch + "/s.solb");
    replace_all(a, "@F", scratch + "/f.solb");
    replace_all(a, "@D", scratch);
  }
  args.push_back("--dry-run");
  args.push_back("-q");
  const int code = metrica::cli::run_command_line(args);
  metrica::log::set_level(metrica::log::Level::normal);
  if (code < 0 || code > 2) std::abort();
  return 0;
}
