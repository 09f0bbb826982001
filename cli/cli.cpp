#include "cli.hpp"

#include <metrica/error.hpp>
#include <metrica/input_checks.hpp>
#include <metrica/io/atomic_file.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/io/output_set.hpp>
#include <metrica/log.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/pipeline/adapt_settings.hpp>
#include <metrica/policies/speculative.hpp>
#include <metrica/policies/threads.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <strings.h>
#include <unistd.h>

namespace metrica::cli {

namespace {
constexpr int kThreadsPerCore = 8;

// OpenMP's threads sleep as soon as they wait (main.cpp sets it unless
// the environment chooses).
bool passive_waiting() {
  const char* policy = std::getenv("OMP_WAIT_POLICY");
  return policy != nullptr && strcasecmp(policy, "passive") == 0;
}
}  // namespace

Options::Options(std::string command, std::string usage, std::string description)
    : command_(std::move(command)), usage_(std::move(usage)), description_(std::move(description)), own_("Options") {}

bool Options::parse(const std::vector<std::string>& args) {
  po::options_description common("Common options");
  common.add_options()("help,h", "print this help and exit")("verbose,v", "print more detail (timings, warnings)")(
      "quiet,q", "print only errors")(
      "dry-run", "check the options and the inputs, print what would be done, compute and write nothing")(
      "threads", po::value<int>()->value_name("N"),
      "threads for parallel work (default: all cores, fewer while other processes keep cores busy; at most 8 per "
      "core)");
  po::options_description all;
  all.add(own_).add(common);
  try {
    po::store(po::command_line_parser(args).options(all).positional(positional_).run(), vm_);
    po::notify(vm_);
  } catch (const po::error& e) {
    // Boost's message substitutes %value%-style placeholders until none is
    // left: an argument holding one made what() loop forever (`cube --n
    // %value%`, found by fuzz_options). Such a command line gets a message
    // of our own.
    for (const std::string& a : args)
      for (const char* p : {"%value%", "%canonical_option%", "%prefix_option%", "%original_token%", "%option%"})
        if (a.find(p) != std::string::npos)
          throw UsageError(
              fmt::format("{}: invalid argument '{}' (bad value, or an option it does not take)", command_, a));
    throw UsageError(fmt::format("{}: {}", command_, e.what()));
  }
  // An option that takes a value takes the next word, even another
  // option: `--output-dir --dry-run` made a folder named "--dry-run" and
  // ran the whole loop. No value of ours starts with "--".
  for (const auto& [name, value] : vm_) {
    const auto* text = boost::any_cast<std::string>(&value.value());
    if (text != nullptr && text->starts_with("--"))
      throw UsageError(fmt::format("{}: --{} needs a value, got the option {}", command_, name, *text));
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
  } else if (std::getenv("OMP_NUM_THREADS") == nullptr && passive_waiting()) {
    // No thread count given: one per core, fewer while other processes
    // keep cores busy (a thread sharing a core with a busy process holds
    // every pass back). Only with passive waiting: threads spinning
    // between passes would count as load.
    Speculative::settings().follow_load = true;
  }
  if (vm_.count("format-version")) in_range("format-version", 1, 4);
  // Outputs: a known extension (usage), a file that can be written (input);
  // "-" is standard output (in the output's first format), for one output
  // at most, and then what the command prints goes to standard error.
  const std::string* to_standard_output = nullptr;
  for (const auto& out : outputs_) {
    if (!vm_.count(out.name)) continue;
    const auto path = vm_[out.name].as<std::string>();
    if (io::is_standard_output(path)) {
      if (to_standard_output != nullptr)
        throw UsageError(fmt::format("{}: --{} and --{} are both standard output ('-'); give one of them a file",
                                     command_, *to_standard_output, out.name));
      to_standard_output = &out.name;
      continue;
    }
    if (!out.formats.empty() &&
        std::find(out.formats.begin(), out.formats.end(), io::format_of(path)) == out.formats.end()) {
      std::string list;
      for (auto f : out.formats) list += std::string(list.empty() ? "" : ", ") + io::to_string(f);
      throw UsageError(fmt::format("{}: --{} {}: unknown format (use {})", command_, out.name, path, list));
    }
    io::writable_target(path);
  }
  if (to_standard_output != nullptr && !dry_run()) io::divert_standard_output();
  return true;
}

double Options::positive(const char* name, double hi) const {
  const double x = get<double>(name);
  if (!(x > 0.0 && x <= hi))
    throw_out_of_range(name, hi < 1e300 ? fmt::format("in (0, {}]", hi) : std::string("finite and > 0"),
                       fmt::format("{}", x));
  return x;
}

MetricBounds Options::size_bounds() const {
  MetricBounds b;
  if (has("hmin")) b.hmin = positive("hmin");
  if (has("hmax")) b.hmax = positive("hmax");
  if (b.hmin > b.hmax) throw UsageError(command_ + ": --hmin is larger than --hmax");
  return b;
}

void Options::throw_out_of_range(const char* name, const std::string& domain, const std::string& value) const {
  throw UsageError(fmt::format("{}: --{} must be {} (got {})", command_, name, domain, value));
}

void Options::input(const char* what) {
  own_.add_options()("input,i", po::value<std::string>()->value_name("FILE"), what);
  positional_.add("input", 1);
}

void Options::output(const char* what, std::initializer_list<io::FileFormat> formats) {
  own_.add_options()("output,o", po::value<std::string>()->value_name("FILE"), what);
  positional_.add("output", 1);
  outputs_.push_back({"output", formats});
}

void Options::output_option(const char* name, const char* what, std::initializer_list<io::FileFormat> formats) {
  own_.add_options()(name, po::value<std::string>()->value_name("FILE"), what);
  outputs_.push_back({name, formats});
}

void Options::msh_binary() {
  own_.add_options()("binary", "write .msh outputs in gmsh's binary encoding (ASCII by default)");
}

void Options::format_version(const char* what) {
  own_.add_options()("format-version", po::value<int>()->value_name("V"), what);
}

std::string Options::required(const char* name, const char* what) const {
  if (!vm_.count(name))
    throw UsageError(fmt::format("{}: missing {} (see metrica {} --help)", command_, what, command_));
  return vm_[name].as<std::string>();
}

void Options::one_of(std::initializer_list<const char*> names, const char* what) const {
  int given = 0;
  for (const char* name : names) given += has(name) ? 1 : 0;
  if (given != 1) throw UsageError(fmt::format("{}: give {}", command_, what));
}

void Options::metric_source(const char* file_what) {
  add()("metric,m", po::value<std::string>()->value_name("FILE"), file_what)(
      "analytic", po::value<std::string>()->value_name("NAME"), "analytic metric: linear, polar-1, polar-2");
}

std::optional<double> ridge_angle(const Options& o) {
  if (o.has("geometry")) {
    // On a model its surfaces are the mesh's ids, its curves the ridges.
    if (o.has("ridge-angle"))
      throw UsageError(
          fmt::format("{}: --ridge-angle and --geometry: on a model the ridges are its curves", o.command()));
    return 180.0;
  }
  if (!o.has("ridge-angle")) return std::nullopt;
  return o.in_range("ridge-angle", 0.0, 180.0);
}

LoadedMesh load_mesh(const std::string& path, Valid valid, std::optional<double> ridge_angle) {
  LoadedMesh out;
  Stopwatch clock;
  out.data = io::read_mesh_file(path);
  check_coordinates(out.data, path);
  out.read_seconds = clock.seconds();
  clock.restart();
  BuildOptions opt;
  opt.source = path;
  opt.require_boundary_triangles = valid == Valid::required;
  if (ridge_angle) {
    opt.ridge_angle = *ridge_angle;
    opt.split_every_surface = true;
  }
  out.mesh = build_mesh(out.data, opt);
  out.build_seconds = clock.seconds();
  log::info("read {} in {:.3f} s, built adjacency in {:.3f} s", path, out.read_seconds, out.build_seconds);
  if (valid == Valid::required) check_valid_input(out.mesh, path);
  return out;
}

PartRunner sweep_runner(std::size_t n, bool serial) { return serial ? PartRunner{} : part_runner<Speculative>(n); }

void max_tets_option(Options& o) {
  static const std::string help = fmt::format(
      "refuse a run predicted to make more than N tets (default: what 90% of this machine's memory holds, {} bytes "
      "per tet)",
      kBytesPerTet);
  o.add()("max-tets", po::value<double>()->value_name("N"), help.c_str());
}

double check_predicted_size(const Options& o, double complexity, const std::string& what) {
  return metrica::check_predicted_size(complexity, o.has("max-tets") ? o.positive("max-tets") : 0.0, o.command(), what,
                                       "--max-tets N raises it; the default is what 90% of this machine's memory holds")
      .tets;
}

void declare_setting(Options& o, const AdaptSetting& s, const AdaptOptions& defaults) {
  const double d = s.get(defaults);
  const std::string name(s.name), value_name(s.value_name), help(s.help);
  o.add()(name.c_str(), po::value<double>()->default_value(d, fmt::format("{:.4g}", d))->value_name(value_name),
          help.c_str());
}

void read_setting(const Options& o, const AdaptSetting& s, AdaptOptions& into) {
  const std::string name(s.name);
  const double x = o.get<double>(name.c_str());
  if (!s.accepts(x)) o.throw_out_of_range(name.c_str(), s.domain(), fmt::format("{}", x));
  s.set(into, x);
}

po::typed_value<double>* number_option(double default_value) {
  return po::value<double>()->default_value(default_value, fmt::format("{}", default_value));
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
