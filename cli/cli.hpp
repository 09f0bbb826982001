// Shared pieces of the `metrica` command: option parsing with the common
// options, exit codes, and aligned output for people.
#pragma once

#include <metrica/error.hpp>
#include <metrica/geometry/cad_model.hpp>
#include <metrica/io/file_format.hpp>
#include <metrica/io/mesh_data.hpp>
#include <metrica/mesh.hpp>
#include <metrica/metrics/metric_bounds.hpp>
#include <metrica/part_runner.hpp>
#include <metrica/pipeline/predicted_size.hpp>

#include <boost/program_options.hpp>
#include <fmt/core.h>

#include <cmath>
#include <initializer_list>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace metrica {
struct AdaptOptions;
struct AdaptSetting;
}  // namespace metrica

namespace metrica::cli {

namespace po = boost::program_options;

// Exit codes: 0 success, 1 invalid input or failed run or check, 2 bad
// usage (an unknown option, a missing argument, an option or argument out
// of its domain). Usage is checked before any file is read.
inline constexpr int kOk = 0;
inline constexpr int kInvalid = 1;
inline constexpr int kUsage = 2;

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Command {
  const char* name;
  const char* summary;
  int (*run)(const std::vector<std::string>& args);
};

const std::vector<Command>& commands();

// The whole command line after the program name: runs the command in an
// io::OutputSet committed only when it returns 0, maps errors to exit codes
// and prints them. Used by main() and by the option fuzzer.
int run_command_line(const std::vector<std::string>& args);
// This process's MPI rank (0 alone): errors every rank meets alike are
// printed by rank 0 only.
void set_process_rank(int rank);

// A subcommand's options: its own plus the common ones (-h, -v, -q,
// --threads), and positional names. parse() returns false when --help was
// asked for (and printed).
class Options {
 public:
  Options(std::string command, std::string usage, std::string description);
  po::options_description_easy_init add() { return own_.add_options(); }
  void positional(const char* name, int max_count) { positional_.add(name, max_count); }
  // The common -i/--input and -o/--output, each also accepted
  // positionally (input before output, in the order these are called).
  // An output's extension must be one of `formats` (none: any), and the
  // file must be writable (io::writable_target): both checked by parse().
  void input(const char* what);
  void output(const char* what, std::initializer_list<io::FileFormat> formats);
  // Another output option (--vtu FILE, --csv FILE, ...), checked alike.
  void output_option(const char* name, const char* what, std::initializer_list<io::FileFormat> formats);
  // --format-version V (libMeshb version to write); 0 when not given.
  void format_version(const char* what);
  int format_version() const { return has("format-version") ? in_range("format-version", 1, 4) : 0; }
  // --binary: .msh outputs in gmsh's binary encoding (ASCII by default;
  // libMeshb files choose by extension).
  void msh_binary();
  io::Encoding msh_encoding() const { return has("binary") ? io::Encoding::binary : io::Encoding::ascii; }
  bool parse(const std::vector<std::string>& args);
  // --dry-run: the options and inputs are checked, nothing is computed or
  // written (the command says what it would do).
  bool dry_run() const { return has("dry-run"); }
  const po::variables_map& vm() const { return vm_; }
  bool has(const char* name) const { return vm_.count(name) != 0; }
  template <class T>
  T get(const char* name) const {
    return vm_[name].as<T>();
  }
  // A required string option, with a usage error naming it if missing.
  std::string required(const char* name, const char* what) const;
  // Exactly one of the options `names` given, else a usage error that
  // lists them (`what`: how the help spells them, "-m METRIC or
  // --analytic NAME").
  void one_of(std::initializer_list<const char*> names, const char* what) const;
  // The metric a command reads: -m FILE (`file_what` says what the file
  // holds) or --analytic NAME; one_of checks that one is given.
  void metric_source(const char* file_what);
  // A numeric option's value checked against its domain [lo, hi] (NaN is
  // refused): a usage error names the option, the domain and the value.
  template <class T>
  T in_range(const char* name, T lo, T hi) const {
    const T x = get<T>(name);
    if (!(x >= lo && x <= hi)) throw_out_of_range(name, fmt::format("in [{}, {}]", lo, hi), fmt::format("{}", x));
    return x;
  }
  // A real option that must be finite and > 0 (and at most hi).
  double positive(const char* name, double hi = 1e300) const;
  // f() (which reads option values: a name, a choice of policies) with its
  // InputError turned into a usage error naming the command.
  template <class F>
  auto as_usage(F&& f) const -> decltype(f()) {
    try {
      return f();
    } catch (const InputError& e) {
      throw UsageError(command_ + ": " + e.what());
    }
  }
  // An optional option whose value is a name, parsed by `from_name`
  // (analytic_metric_from_name, ...): an unknown name is a usage error.
  template <class From>
  auto named(const char* name, From&& from_name) const -> std::optional<decltype(from_name(std::string()))> {
    if (!has(name)) return std::nullopt;
    return as_usage([&] { return from_name(get<std::string>(name)); });
  }
  // --hmin / --hmax as bounds on a metric's sizes (usage-checked).
  MetricBounds size_bounds() const;
  [[noreturn]] void throw_out_of_range(const char* name, const std::string& domain, const std::string& value) const;
  const std::string& command() const { return command_; }

 private:
  std::string command_, usage_, description_;
  po::options_description own_;
  po::positional_options_description positional_;
  po::variables_map vm_;
  struct Output {
    std::string name;
    std::vector<io::FileFormat> formats;
  };
  std::vector<Output> outputs_;
};

// Reads a mesh file and builds the Mesh, reporting time when verbose. The
// coordinates are checked (finite, within +-1e12); with Valid::required
// the mesh must pass validate() (orientation, adjacency, a closed manifold
// boundary), else an InputError names the first problems.
struct LoadedMesh {
  io::MeshData data;
  Mesh mesh;
  double read_seconds = 0, build_seconds = 0;
};
enum class Valid { required, not_required };
// `ridge_angle`: every surface split at that angle (surface_angles.hpp);
// without it, only a boundary without ids, or of one id, at 45 degrees.
LoadedMesh load_mesh(const std::string& path, Valid valid = Valid::required,
                     std::optional<double> ridge_angle = std::nullopt);
// --ridge-angle, checked (0 to 180 degrees), when given; with --geometry
// 180 (the ids are the model's surfaces; both together: UsageError).
std::optional<double> ridge_angle(const Options& o);

// --max-tets: the most tetrahedra a run may be asked to make; by default
// what 90% of the machine's memory holds (pipeline/predicted_size.hpp).
// Adds --max-tets to a command's options.
void max_tets_option(Options& o);
// Refuses (InputError) a run whose predicted output, kTetsPerComplexity x
// `complexity`, exceeds --max-tets; returns the prediction.
double check_predicted_size(const Options& o, double complexity, const std::string& what);

// --geometry FILE: opens the CAD model and associates the mesh's boundary
// vertices with it (InputError when they do not match), then says how far
// the input is from it, whose recorded parameters were not taken, and (when
// `adapting`) that the vertices off it go onto it in the first stage.
std::unique_ptr<CadModel> open_geometry(const std::string& path, Mesh& mesh, const io::MeshData* input,
                                        bool adapting = false);
// One line: how far the boundary vertices are from their entities.
std::string model_distance_text(const Mesh& mesh, const CadModel& model);

// What runs a command's sweeps over `n` items outside the operators
// (validation, the formatting of ASCII outputs): the default policy's
// part_runner (the --threads threads, one below its sweep size), or the
// calling thread alone when `serial` (--concurrency serial).
PartRunner sweep_runner(std::size_t n, bool serial = false);

// An option of the standard adaptation's settings table
// (pipeline/adapt_settings.hpp): declared with the default `defaults`
// hold, read back into `into` after the table's range check (a usage
// error names the option, its domain and the value).
void declare_setting(Options& o, const AdaptSetting& s, const AdaptOptions& defaults);
void read_setting(const Options& o, const AdaptSetting& s, AdaptOptions& into);

// A number option whose default the help shows as the library states it
// ("0.3", not Boost's "0.29999999999999999").
po::typed_value<double>* number_option(double default_value);

// Human-readable sizes and numbers.
std::string count_text(std::size_t n);

}  // namespace metrica::cli
