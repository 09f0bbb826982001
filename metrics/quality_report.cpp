#include <metrica/error.hpp>
#include <metrica/mesh_edges.hpp>
#include <metrica/metrics/complexity.hpp>
#include <metrica/metrics/quality_report.hpp>
#include <metrica/metrics/space.hpp>
#include <metrica/metrics/unit_band.hpp>
#include <metrica/numbering.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace metrica {

namespace {

Histogram make_histogram(std::vector<double> edges) {
  Histogram h;
  h.counts.assign(edges.size() - 1, 0);
  h.edges = std::move(edges);
  return h;
}

// NaN belongs to no bin (the caller refuses the report).
void add(Histogram& h, double x) {
  if (std::isnan(x)) return;
  if (x < h.edges.front()) {
    ++h.below;
    return;
  }
  if (x >= h.edges.back()) {
    // The last bin is closed on the right (Q = 1 belongs to [0.9, 1]).
    if (x == h.edges.back() && h.edges.back() == 1.0)
      ++h.counts.back();
    else
      ++h.above;
    return;
  }
  const auto it = std::upper_bound(h.edges.begin(), h.edges.end(), x);
  ++h.counts[static_cast<std::size_t>(it - h.edges.begin()) - 1];
}

struct Accumulator {
  SampleStats s{std::numeric_limits<double>::infinity(), 0.0, -std::numeric_limits<double>::infinity(), 0};
  double sum = 0.0;
  void add(double x) {
    s.min = std::min(s.min, x);
    s.max = std::max(s.max, x);
    sum += x;
    ++s.count;
  }
  void merge(const Accumulator& o) {
    s.min = std::min(s.min, o.s.min);
    s.max = std::max(s.max, o.s.max);
    sum += o.sum;
    s.count += o.s.count;
  }
  SampleStats done() const {
    SampleStats r = s;
    if (r.count == 0) return {};
    r.mean = sum / static_cast<double>(r.count);
    return r;
  }
};

// One block's share of a measure: its extremes and sum, its histogram, and
// the counts of two thresholds. Summed block by block in block order, so
// that the report is the same for any runner.
struct BlockMeasure {
  Accumulator acc;
  Histogram hist;
  std::size_t first = 0, second = 0;
  void add_measure(double x) {
    acc.add(x);
    add(hist, x);
  }
  void merge_into(BlockMeasure& all) const {
    all.acc.merge(acc);
    for (std::size_t i = 0; i < hist.counts.size(); ++i) all.hist.counts[i] += hist.counts[i];
    all.hist.below += hist.below;
    all.hist.above += hist.above;
    all.first += first;
    all.second += second;
  }
};

std::vector<BlockMeasure> block_measures(std::size_t blocks, const std::vector<double>& bins) {
  std::vector<BlockMeasure> m(blocks);
  for (auto& b : m) b.hist = make_histogram(bins);
  return m;
}

BlockMeasure sum_blocks(const std::vector<BlockMeasure>& blocks, const std::vector<double>& bins) {
  BlockMeasure all;
  all.hist = make_histogram(bins);
  for (const auto& b : blocks) b.merge_into(all);
  return all;
}

// The error of a report some measure of which is NaN or infinite: the
// metric (or a coordinate) is degenerate there. Names the first such edge
// or tet and the metrics at its ends.
template <MetricSpace S>
std::string not_finite_message(const Mesh& mesh) {
  const auto where = [&](std::initializer_list<VertexId> vertices) {
    std::string out;
    for (VertexId v : vertices) {
      const Point& p = mesh.point(v);
      const Sym6& m = mesh.metric(v);
      out += fmt::format("\n  vertex {} at ({:.6g}, {:.6g}, {:.6g}): metric {:.6g} {:.6g} {:.6g} {:.6g} {:.6g} {:.6g}",
                         numbered(v), p.x(), p.y(), p.z(), m[0], m[1], m[2], m[3], m[4], m[5]);
    }
    return out;
  };
  std::string found;
  for_each_unique_edge(mesh, [&](VertexId a, VertexId b) {
    if (found.empty() && !std::isfinite(S::edge_length(mesh, a, b)))
      found = fmt::format("the metric length of edge ({} {}) is {}{}", numbered(a), numbered(b),
                          S::edge_length(mesh, a, b), where({a, b}));
  });
  for (TetId t = 0; found.empty() && t < mesh.tet_capacity(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    const auto& v = mesh.tet(t);
    const double q = S::mean_ratio(mesh, v);
    if (!std::isfinite(q))
      found = fmt::format("the mean ratio of tet {} is {}{}", numbered(t), q, where({v[0], v[1], v[2], v[3]}));
  }
  return fmt::format(
      "quality report: {} (a metric with non-finite, huge or vanishing entries, or non-finite "
      "coordinates)",
      found.empty() ? std::string("a cached mean ratio is not finite") : found);
}

template <MetricSpace S>
QualityReport report_in(const Mesh& mesh, const QualityReportOptions& o) {
  QualityReport r;
  r.space = std::string(S::name);
  r.vertices = mesh.num_vertices();
  r.tets = mesh.num_tets();
  std::vector<double> length_bins;
  for (int k = -8; k <= 8; ++k) length_bins.push_back(std::exp2(0.5 * k));
  std::vector<double> q_bins;
  for (int k = 0; k <= 10; ++k) q_bins.push_back(0.1 * k);

  // Edge by edge, not from a list of them: the report of a large mesh
  // must not hold more than the adaptation did. One measure per block of
  // lower ends (first: edges in the unit band).
  auto edge_blocks = block_measures(mesh.vertex_capacity() / kEdgeBlockVertices + 1, length_bins);
  for_each_unique_edge(
      mesh,
      [&](VertexId a, VertexId b) {
        const double l = S::edge_length(mesh, a, b);
        BlockMeasure& m = edge_blocks[a / kEdgeBlockVertices];
        m.add_measure(l);
        m.first += kUnitBand.contains(l);
      },
      o.run);
  // Tets in blocks of kTetBlock (first, second: below 0.1 and 0.3).
  constexpr std::size_t kTetBlock = std::size_t{1} << 16;
  const std::size_t nt = mesh.tet_capacity();
  auto tet_blocks = block_measures(nt / kTetBlock + 1, q_bins);
  const std::size_t parts = std::clamp<std::size_t>(o.run.parts, 1, tet_blocks.size());
  o.run(parts, [&](std::size_t p) {
    const auto [b0, b1] = part_slice(tet_blocks.size(), parts, p);
    for (std::size_t b = b0; b < b1; ++b) {
      BlockMeasure& m = tet_blocks[b];
      for (auto t = static_cast<TetId>(b * kTetBlock); t < std::min(nt, (b + 1) * kTetBlock); ++t) {
        if (!mesh.tet_alive(t)) continue;
        const double q = o.cached_quality ? cached_mean_ratio<S>(mesh, t) : S::mean_ratio(mesh, mesh.tet(t));
        m.add_measure(q);
        m.first += q < 0.1;
        m.second += q < 0.3;
      }
    }
  });
  const BlockMeasure edges = sum_blocks(edge_blocks, length_bins), tets = sum_blocks(tet_blocks, q_bins);
  const Accumulator& len = edges.acc;
  const Accumulator& qual = tets.acc;
  r.edges = len.s.count;
  r.length_histogram = edges.hist;
  r.quality_histogram = tets.hist;
  const std::size_t unit = edges.first, below01 = tets.first, below03 = tets.second;
  // A NaN or infinite measure says the metric (or a coordinate) is
  // degenerate: no report rather than one that reads "nan".
  if (!std::isfinite(len.sum) || !std::isfinite(qual.sum)) throw InputError(not_finite_message<S>(mesh));
  r.length = len.done();
  r.quality = qual.done();
  if (r.edges) r.unit_length_share = static_cast<double>(unit) / static_cast<double>(r.edges);
  if (r.tets) {
    r.quality_below_01 = static_cast<double>(below01) / static_cast<double>(r.tets);
    r.quality_below_03 = static_cast<double>(below03) / static_cast<double>(r.tets);
  }
  r.complexity = complexity(mesh);
  if (r.complexity > 0) r.vertices_per_complexity = static_cast<double>(r.vertices) / r.complexity;
  r.volume = mesh.volume();
  return r;
}

std::string histogram_text(const Histogram& h, const char* name, const char* format) {
  std::string out = fmt::format("  {} histogram\n", name);
  std::size_t peak = std::max(h.below, h.above);
  for (auto c : h.counts) peak = std::max(peak, c);
  auto bar = [&](std::size_t c) { return std::string(peak ? (40 * c + peak - 1) / peak : 0, '#'); };
  auto num = [&](double x) { return fmt::format(fmt::runtime(format), x); };
  if (h.below) out += fmt::format("    {:>17} {:>10} {}\n", "< " + num(h.edges.front()), h.below, bar(h.below));
  for (std::size_t i = 0; i < h.counts.size(); ++i)
    out += fmt::format("    [{:>7},{:>7}) {:>10} {}\n", num(h.edges[i]), num(h.edges[i + 1]), h.counts[i],
                       bar(h.counts[i]));
  if (h.above) out += fmt::format("    {:>17} {:>10} {}\n", ">= " + num(h.edges.back()), h.above, bar(h.above));
  return out;
}

}  // namespace

QualityReport quality_report(const Mesh& mesh, std::string_view space, const QualityReportOptions& options) {
  if (!mesh.has_metric()) throw InputError("quality report: the mesh has no metric");
  return with_policy<Spaces>("metric space", space, [&]<class S>() { return report_in<S>(mesh, options); });
}

QualityMeasures quality_measures(const Mesh& mesh, std::string_view space) {
  if (!mesh.has_metric()) throw InputError("quality measures: the mesh has no metric");
  return with_policy<Spaces>("metric space", space, [&]<class S>() {
    QualityMeasures m;
    for_each_unique_edge(mesh, [&](VertexId a, VertexId b) {
      m.edges.push_back({a, b});
      m.lengths.push_back(S::edge_length(mesh, a, b));
    });
    m.mean_ratios.reserve(mesh.num_tets());
    for (TetId t = 0; t < mesh.tet_capacity(); ++t)
      if (mesh.tet_alive(t)) m.mean_ratios.push_back(S::mean_ratio(mesh, mesh.tet(t)));
    return m;
  });
}

std::string format_report(const QualityReport& r) {
  std::string out;
  out += fmt::format("quality in the metric ({} interpolation)\n", r.space);
  out += fmt::format("  vertices {}  edges {}  tets {}\n", r.vertices, r.edges, r.tets);
  out += fmt::format("  edge length  min {:.4f}  mean {:.4f}  max {:.4f}\n", r.length.min, r.length.mean, r.length.max);
  out +=
      fmt::format("  mean ratio   min {:.4f}  mean {:.4f}  max {:.4f}\n", r.quality.min, r.quality.mean, r.quality.max);
  out += fmt::format("  edges in [1/sqrt2, sqrt2]  {:.2f}%\n", 100.0 * r.unit_length_share);
  out += fmt::format("  tets with Q < 0.1  {:.3f}%   Q < 0.3  {:.3f}%\n", 100.0 * r.quality_below_01,
                     100.0 * r.quality_below_03);
  out += fmt::format("  complexity {:.6g}  vertices / complexity {:.4f}  volume {:.6g}\n", r.complexity,
                     r.vertices_per_complexity, r.volume);
  out += histogram_text(r.length_histogram, "edge length", "{:.3f}");
  out += histogram_text(r.quality_histogram, "mean ratio", "{:.1f}");
  return out;
}

std::string report_csv(const QualityReport& r) {
  std::string out = "section,key,lo,hi,value\n";
  auto row = [&](const char* key, double v) { out += fmt::format("summary,{},,,{:.17g}\n", key, v); };
  row("vertices", static_cast<double>(r.vertices));
  row("edges", static_cast<double>(r.edges));
  row("tets", static_cast<double>(r.tets));
  row("length_min", r.length.min);
  row("length_mean", r.length.mean);
  row("length_max", r.length.max);
  row("quality_min", r.quality.min);
  row("quality_mean", r.quality.mean);
  row("quality_max", r.quality.max);
  row("unit_length_share", r.unit_length_share);
  row("quality_below_0.1", r.quality_below_01);
  row("quality_below_0.3", r.quality_below_03);
  row("complexity", r.complexity);
  row("vertices_per_complexity", r.vertices_per_complexity);
  row("volume", r.volume);
  auto hist = [&](const char* name, const Histogram& h) {
    out += fmt::format("{},below,,{:.17g},{}\n", name, h.edges.front(), h.below);
    for (std::size_t i = 0; i < h.counts.size(); ++i)
      out += fmt::format("{},bin,{:.17g},{:.17g},{}\n", name, h.edges[i], h.edges[i + 1], h.counts[i]);
    out += fmt::format("{},above,{:.17g},,{}\n", name, h.edges.back(), h.above);
  };
  hist("length_histogram", r.length_histogram);
  hist("quality_histogram", r.quality_histogram);
  return out;
}

}  // namespace metrica
