#include <metrica/error.hpp>
#include <metrica/mesh_edges.hpp>
#include <metrica/metrics/complexity.hpp>
#include <metrica/metrics/quality_report.hpp>
#include <metrica/metrics/space.hpp>
#include <metrica/metrics/unit_band.hpp>

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
  SampleStats done() const {
    SampleStats r = s;
    if (r.count == 0) return {};
    r.mean = sum / static_cast<double>(r.count);
    return r;
  }
};

template <MetricSpace S>
QualityReport report_in(const Mesh& mesh) {
  QualityReport r;
  r.space = std::string(S::name);
  r.vertices = mesh.num_vertices();
  r.tets = mesh.num_tets();
  std::vector<double> length_edges;
  for (int k = -8; k <= 8; ++k) length_edges.push_back(std::exp2(0.5 * k));
  r.length_histogram = make_histogram(length_edges);
  std::vector<double> q_edges;
  for (int k = 0; k <= 10; ++k) q_edges.push_back(0.1 * k);
  r.quality_histogram = make_histogram(q_edges);

  Accumulator len, qual;
  std::size_t unit = 0;
  // Edge by edge, not from a list of them: the report of a large mesh
  // must not hold more than the adaptation did.
  for_each_unique_edge(mesh, [&](VertexId a, VertexId b) {
    const double l = S::edge_length(mesh, a, b);
    len.add(l);
    add(r.length_histogram, l);
    unit += kUnitBand.contains(l);
    ++r.edges;
  });
  std::size_t below01 = 0, below03 = 0;
  for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    const double q = S::mean_ratio(mesh, mesh.tet(t));
    qual.add(q);
    add(r.quality_histogram, q);
    below01 += q < 0.1;
    below03 += q < 0.3;
  }
  // A NaN or infinite measure says the metric (or a coordinate) is
  // degenerate: no report rather than one that reads "nan".
  if (!std::isfinite(len.sum) || !std::isfinite(qual.sum))
    throw InputError(fmt::format(
        "quality report: {} is not finite on some {} (a metric with non-finite, huge or "
        "vanishing entries, or non-finite coordinates)",
        !std::isfinite(len.sum) ? "the metric length" : "the mean ratio", !std::isfinite(len.sum) ? "edge" : "tet"));
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

QualityReport quality_report(const Mesh& mesh, std::string_view space) {
  if (!mesh.has_metric()) throw InputError("quality report: the mesh has no metric");
  return with_policy<Spaces>("metric space", space, [&]<class S>() { return report_in<S>(mesh); });
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
