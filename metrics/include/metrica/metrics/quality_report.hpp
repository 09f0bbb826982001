// The UGAWG quality report of a mesh in its metric (docs/architecture.md, "Quality
// measures"; seed appendix A): edge lengths (UGAWG formula) and mean
// ratios (metric at the centroid), their extremes, means and histograms,
// the share of edges in [1/sqrt 2, sqrt 2] (conformity), the share of tets
// with Q < 0.1 and < 0.3, and the metric complexity.
#pragma once

#include <metrica/mesh.hpp>
#include <metrica/part_runner.hpp>

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace metrica {

struct Histogram {
  std::vector<double> edges;         // bin boundaries, size bins + 1
  std::vector<std::size_t> counts;   // per bin
  std::size_t below = 0, above = 0;  // outside the first / last boundary
};

struct SampleStats {
  double min = 0, mean = 0, max = 0;
  std::size_t count = 0;
};

struct QualityReport {
  std::string space;
  std::size_t vertices = 0, edges = 0, tets = 0;
  SampleStats length, quality;
  double unit_length_share = 0;                       // edges with L in [1/sqrt 2, sqrt 2]
  double quality_below_01 = 0, quality_below_03 = 0;  // shares of tets
  double complexity = 0;
  double vertices_per_complexity = 0;
  double volume = 0;
  Histogram length_histogram;   // log2 bins of width 1/2 from 2^-4 to 2^4
  Histogram quality_histogram;  // bins of 0.1 on [0, 1]
};

struct QualityReportOptions {
  // The sweeps over edges and tets on these parts (a Concurrency policy's
  // part_runner); the report is the same for any runner.
  PartRunner run;
  // Read and fill the mesh's quality cache: only while it is known to hold
  // this space's mean ratios, as after adapt in the same space.
  bool cached_quality = false;
};

// The mesh must carry a metric (Mesh::has_metric); `space` is one of the
// names of Spaces (InputError otherwise).
QualityReport quality_report(const Mesh& mesh, std::string_view space = "log-euclidean",
                             const QualityReportOptions& options = {});

// The measures the report sums up, one by one: each edge (lower id first,
// by lower end) with its length, and each live tet's mean ratio in id
// order; for plots and filters of one's own (the Python module's).
struct QualityMeasures {
  std::vector<std::array<VertexId, 2>> edges;
  std::vector<double> lengths;
  std::vector<double> mean_ratios;
};
QualityMeasures quality_measures(const Mesh& mesh, std::string_view space = "log-euclidean");

// For people: a summary and both histograms as text.
std::string format_report(const QualityReport& r);
// Tidy CSV (section,key,lo,hi,value): summary rows, then one row per bin.
std::string report_csv(const QualityReport& r);

}  // namespace metrica
