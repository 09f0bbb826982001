#include "cli.hpp"

#include <metrica/log.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/policies/threads.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <iostream>

namespace metrica::cli {

namespace {
constexpr int kThreadsPerCore = 8;
}  // namespace

Options::Options(std::string command, std::string usage, std::string description)
    : command_(std::move(command)), usage_(std::move(usage)), description_(std::move(description)),
      own_("Options") {}

bool Options::parse(const std::vector<std::string>& args) {
  po::options_description common("Common options");
  common.add_options()("help,h", "print this help and exit")("verbose,v", "print more detail (timings, warnings)")(
      "quiet,q", "print only errors")("threads", po::value<int>()->value_name("N"),
                                      "threads for parallel work (default: all cores; at most 8 per core)");
  po::options_description all;
  all.add(own_).add(common);
  try {
    po::store(po::command_line_parser(args).options(all).positional(positional_).run(), vm_);
    po::notify(vm_);
  } catch (const po::error& e) {
    throw UsageError(fmt::format("{}: {}", command_, e.what()));
  }
  if (vm_.count("help")) {
    std::cout << "usage: metrica " << command_ << " " << usage_ << "\n\n" << description_ << "\n\n" << all << "\n";
    return false;
  }
  if (vm_.count("quiet") && vm_.count("verbose")) throw UsageError(command_ + ": -q and -v exclude each other");
  if (vm_.count("quiet")) log::set_level(log::Level::quiet);
  if (vm_.count("verbose")) log::set_level(log::Level::verbose);
  if (vm_.count("threads")) {
    int n = vm_["threads"].as<int>();
    if (n < 1) throw UsageError(fmt::format("{}: --threads must be at least 1, got {}", command_, n));
    // More than a few threads per core only adds contention (and tens of
    // thousands exhaust the process's stacks).
    const int cap = kThreadsPerCore * std::max(1, core_count());
    if (n > cap) {
      log::warn("{}: --threads {} is more than {} per core; using {}", command_, n, kThreadsPerCore, cap);
      n = cap;
    }
    set_thread_count(n);
  }
  return true;
}

void Options::input(const char* what) {
  own_.add_options()("input,i", po::value<std::string>()->value_name("FILE"), what);
  positional_.add("input", 1);
}

void Options::output(const char* what) {
  own_.add_options()("output,o", po::value<std::string>()->value_name("FILE"), what);
  positional_.add("output", 1);
}

void Options::format_version(const char* what) {
  own_.add_options()("format-version", po::value<int>()->value_name("V"), what);
}

std::string Options::required(const char* name, const char* what) const {
  if (!vm_.count(name)) throw UsageError(fmt::format("{}: missing {} (see metrica {} --help)", command_, what, command_));
  return vm_[name].as<std::string>();
}

LoadedMesh load_mesh(const std::string& path) {
  LoadedMesh out;
  Stopwatch clock;
  out.data = io::read_mesh_file(path);
  out.read_seconds = clock.seconds();
  clock.restart();
  BuildOptions opt;
  opt.source = path;
  out.mesh = build_mesh(out.data, opt);
  out.build_seconds = clock.seconds();
  log::info("read {} in {:.3f} s, built adjacency in {:.3f} s", path, out.read_seconds, out.build_seconds);
  return out;
}

std::string bytes_text(double bytes) {
  if (bytes < 1024) return fmt::format("{:.0f} B", bytes);
  if (bytes < 1024.0 * 1024) return fmt::format("{:.1f} KiB", bytes / 1024);
  if (bytes < 1024.0 * 1024 * 1024) return fmt::format("{:.1f} MiB", bytes / (1024.0 * 1024));
  return fmt::format("{:.2f} GiB", bytes / (1024.0 * 1024 * 1024));
}

std::string count_text(std::size_t n) {
  std::string s = std::to_string(n), out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (i > 0 && (s.size() - i) % 3 == 0) out += ',';
    out += s[i];
  }
  return out;
}

}  // namespace metrica::cli
