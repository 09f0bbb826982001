// Mesh::validate(): every invariant of docs/architecture.md, reported precisely.
#pragma once

#include <metrica/mesh.hpp>
#include <metrica/part_runner.hpp>

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace metrica {

struct ValidateOptions {
  // When set, the total volume must equal it within the relative tolerance
  // (operators conserve volume up to round-off).
  std::optional<double> expected_volume;
  double volume_tolerance = 1e-10;
  // Messages kept per check; the counts stay exact beyond it.
  std::size_t max_messages_per_check = 20;
  // The per-tet checks run on its parts; the report is the same for any
  // number of parts.
  PartRunner run;
};

class ValidationReport {
 public:
  struct Problem {
    std::string check;  // "orientation", "adjacency", "boundary", ...
    std::string message;
  };

  void add(const std::string& check, std::string message, std::size_t max_messages);
  // Appends `later`'s problems and counts, as if they were added after
  // this report's.
  void append(const ValidationReport& later, std::size_t max_messages);
  bool ok() const { return counts_.empty(); }
  explicit operator bool() const { return ok(); }
  // Number of failures of one check (all of them, kept or not).
  std::size_t count(const std::string& check) const;
  std::size_t total() const;
  const std::vector<Problem>& problems() const { return problems_; }
  const std::map<std::string, std::size_t>& counts() const { return counts_; }
  // "valid", or one line per kept problem and a per-check summary.
  std::string to_string() const;

 private:
  std::vector<Problem> problems_;
  std::map<std::string, std::size_t> counts_;
};

// The checks, in the order they run:
//   "vertices"       a live tet names a dead or out-of-range vertex, or a
//                    vertex twice; live counts disagree with the flags
//   "orientation"    orient3d(v0,v1,v2,v3) <= 0
//   "adjacency"      a neighbour slot that is not mutual or whose face
//                    holds other vertices
//   "boundary"       a boundary face with surface id <= 0, an interior
//                    face with an id
//   "faces"          a triangle that is a face of more than two tets, or
//                    of two that are not neighbours through it
//   "manifold"       a boundary edge not on exactly two boundary faces, or
//                    a boundary vertex whose faces do not form one umbrella
//   "classification" stored ridges or vertex classes differ from a fresh
//                    compute_classification()
//   "vert2tet"       a live vertex whose hint is not a live tet holding it
//   "volume"         the volume differs from the expected one
ValidationReport validate(const Mesh& mesh, const ValidateOptions& options = {});

}  // namespace metrica
