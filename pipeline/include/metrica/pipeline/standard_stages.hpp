// The standard stages compiled once, in the library: for every tuple of
// the policy lists (Spaces x Precisions x Concurrencies x Geometries), the
// passes of the standard pipeline under their standard criteria, the
// standard pipeline itself and adapt<S, P, C, G> are declared here as
// explicit instantiations (extern template) and defined in
// pipeline/adapt_unit.cpp. A program's own pipeline built from the
// Adapter's standard stages therefore compiles none of them; a stage
// under another criterion (flips<MaxMinEdgeWeight>) or another policy is
// compiled where it is used, as any template.
#pragma once

#include <metrica/geometry/cad_geometry.hpp>
#include <metrica/metrics/space.hpp>
#include <metrica/policies/speculative.hpp>
#include <metrica/policy_list.hpp>
#include <metrica/predicates/precision.hpp>

// 1 in the sanitizer builds, which compile the default space and
// precision only, and the AddressSanitizer build the default concurrency
// only too (pipeline/CMakeLists.txt sets both for every user of the
// library).
#ifndef METRICA_DEFAULT_POLICIES_ONLY
#define METRICA_DEFAULT_POLICIES_ONLY 0
#endif
#ifndef METRICA_SPECULATIVE_ONLY
#define METRICA_SPECULATIVE_ONLY 0
#endif

namespace metrica {

// Where boundary vertices go: the start mesh's facets, or a CAD model.
using Geometries = PolicyList<NoGeometry, CadGeometry>;

}  // namespace metrica

// The macros keep one instantiation a line, in the lists' order.
// clang-format off
// The standard stages of one tuple: `kind` is `extern` for the declaration,
// empty for the definition.
#define METRICA_STANDARD_STAGES(kind, S, P, C, G)                                                               \
  kind template OperatorStats collapse_edges<S, P, C, ShapeOnly, G>(Mesh&, const CollapseOptions&, const G&);  \
  kind template OperatorStats refine_edges<S, P, C, ShapeOnly, G>(Mesh&, const RefineOptions&, const G&);      \
  kind template OperatorStats refine_centroids<S, P, C, ShapeOnly, G>(Mesh&, const RefineOptions&, const G&);  \
  kind template OperatorStats reconnect<S, P, C, MinQuality, G>(Mesh&, const ReconnectOptions&, const G&);     \
  kind template OperatorStats reconnect<S, P, C, MetricDelaunay, G>(Mesh&, const ReconnectOptions&, const G&); \
  kind template OperatorStats smooth_vertices<S, P, C, MinQuality, G>(Mesh&, const SmoothOptions&, const G&);  \
  kind template OperatorStats swap_toward_model<S, P, C, G>(Mesh&, const BoundarySwapOptions&, const G&);      \
  kind template OperatorStats flip_interfaces<S, P, C, G>(Mesh&, const InterfaceFlipOptions&, const G&);       \
  kind template Pipeline<Adapter<S, P, C, G>> standard_pipeline<Adapter<S, P, C, G>>(const AdaptOptions&);     \
  kind template const AdaptReport& run_pipeline<Adapter<S, P, C, G>>(Adapter<S, P, C, G>&,                      \
                                                                     const Pipeline<Adapter<S, P, C, G>>&);    \
  kind template AdaptReport adapt<S, P, C, G>(Mesh&, const AdaptOptions&, const AdaptInputs&, const G&);

// The tuple at indices (space, precision, concurrency, geometry) of the lists.
#define METRICA_STANDARD_STAGES_AT(kind, s, p, c, g)                                                   \
  METRICA_STANDARD_STAGES(kind, ::metrica::Spaces::at<s>, ::metrica::Precisions::at<p>,               \
                          ::metrica::Concurrencies::at<c>, ::metrica::Geometries::at<g>)
#define METRICA_STANDARD_STAGES_OF_SPACE(kind, s)                                                          \
  METRICA_STANDARD_STAGES_AT(kind, s, 0, 0, 0) METRICA_STANDARD_STAGES_AT(kind, s, 0, 0, 1)              \
  METRICA_STANDARD_STAGES_AT(kind, s, 0, 1, 0) METRICA_STANDARD_STAGES_AT(kind, s, 0, 1, 1)              \
  METRICA_STANDARD_STAGES_AT(kind, s, 1, 0, 0) METRICA_STANDARD_STAGES_AT(kind, s, 1, 0, 1)              \
  METRICA_STANDARD_STAGES_AT(kind, s, 1, 1, 0) METRICA_STANDARD_STAGES_AT(kind, s, 1, 1, 1)              \
  METRICA_STANDARD_STAGES_AT(kind, s, 2, 0, 0) METRICA_STANDARD_STAGES_AT(kind, s, 2, 0, 1)              \
  METRICA_STANDARD_STAGES_AT(kind, s, 2, 1, 0) METRICA_STANDARD_STAGES_AT(kind, s, 2, 1, 1)
#define METRICA_STANDARD_STAGES_OF_DEFAULTS(kind)                                                        \
  METRICA_STANDARD_STAGES_AT(kind, 0, 0, 0, 0) METRICA_STANDARD_STAGES_AT(kind, 0, 0, 0, 1)              \
  METRICA_STANDARD_STAGES_AT(kind, 0, 0, 1, 0) METRICA_STANDARD_STAGES_AT(kind, 0, 0, 1, 1)
// clang-format on
