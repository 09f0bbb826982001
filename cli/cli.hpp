// Shared pieces of the `metrica` command: option parsing with the common
// options, exit codes, and aligned output for people.
#pragma once

#include <metrica/geometry/cad_model.hpp>
#include <metrica/io/mesh_data.hpp>
#include <metrica/mesh.hpp>

#include <boost/program_options.hpp>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace metrica::cli {

namespace po = boost::program_options;

// Exit codes: 0 success, 1 invalid input or failed check, 2 bad usage.
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
  void input(const char* what);
  void output(const char* what);
  // --format-version V (libMeshb version to write); 0 when not given.
  void format_version(const char* what);
  int format_version() const { return has("format-version") ? get<int>("format-version") : 0; }
  bool parse(const std::vector<std::string>& args);
  const po::variables_map& vm() const { return vm_; }
  bool has(const char* name) const { return vm_.count(name) != 0; }
  template <class T>
  T get(const char* name) const {
    return vm_[name].as<T>();
  }
  // A required string option, with a usage error naming it if missing.
  std::string required(const char* name, const char* what) const;

 private:
  std::string command_, usage_, description_;
  po::options_description own_;
  po::positional_options_description positional_;
  po::variables_map vm_;
};

// Reads a mesh file and builds the Mesh, reporting time when verbose.
struct LoadedMesh {
  io::MeshData data;
  Mesh mesh;
  double read_seconds = 0, build_seconds = 0;
};
LoadedMesh load_mesh(const std::string& path);

// --geometry FILE: opens the CAD model and associates the mesh's boundary
// vertices with it (InputError when they do not match).
std::unique_ptr<CadModel> open_geometry(const std::string& path, Mesh& mesh, const io::MeshData* input);
// One line: how far the boundary vertices are from their entities.
std::string model_distance_text(const Mesh& mesh, const CadModel& model);

// Human-readable sizes and numbers.
std::string bytes_text(double bytes);
std::string count_text(std::size_t n);

}  // namespace metrica::cli
