#include "cli.hpp"

namespace metrica::cli {

int run_cube(const std::vector<std::string>& args);
int run_bootstrap(const std::vector<std::string>& args);
int run_info(const std::vector<std::string>& args);
int run_check(const std::vector<std::string>& args);
int run_convert(const std::vector<std::string>& args);
int run_metric(const std::vector<std::string>& args);
int run_quality(const std::vector<std::string>& args);
int run_adapt(const std::vector<std::string>& args);
int run_pipeline(const std::vector<std::string>& args);
int run_loop(const std::vector<std::string>& args);
int run_interpolate(const std::vector<std::string>& args);
int run_error(const std::vector<std::string>& args);

const std::vector<Command>& commands() {
  static const std::vector<Command> list{
      {"cube", "write a box mesh of n x m x k hexes split into 6 tets each", run_cube},
      {"bootstrap", "write a first mesh of a CAD model (gmsh), its boundary associated with the model", run_bootstrap},
      {"info", "print counts, extent, surfaces, ridges, corners and volume of a mesh", run_info},
      {"check", "read a mesh and check every invariant (exit 1 with a report if invalid)", run_check},
      {"convert", "convert between .mesh, .meshb, .vtu, .su2 (and .sol <-> .solb)", run_convert},
      {"metric", "write a metric field: analytic, multiscale from a field, scaled, bounded, graded", run_metric},
      {"adapt", "adapt a mesh to a metric (file or analytic): collapse, split, flips, smoothing", run_adapt},
      {"pipeline", "run a pipeline composed on the command line from the stage kinds (as Python's Pipeline)",
       run_pipeline},
      {"loop", "the adaptive loop with an analytic field: multiscale metric, adapt, L2 error, repeat", run_loop},
      {"interpolate", "transfer a vertex field from one mesh to another (P1, point location by walking)",
       run_interpolate},
      {"error", "the L2 error of a P1 field against an analytic field or a finer mesh's solution", run_error},
      {"quality", "print the UGAWG quality report of a mesh in a metric (--csv for a table)", run_quality},
  };
  return list;
}

}  // namespace metrica::cli
