// The standard stages compiled once, in the library: for every triple of
// the policy lists (Spaces x Concurrencies x Geometries) the build
// compiles (compiled_policies.hpp, generated from the lists), the passes
// of the standard pipeline under their standard criteria, and per
// precision (Precisions: the metric-Delaunay criterion's only) the
// standard pipeline and adapt<S, P, C, G>, are declared as explicit
// instantiations (extern template, adapt.hpp) and defined in
// pipeline/adapt_unit.cpp. A program's own pipeline built from the
// Adapter's standard stages therefore compiles none of them; a stage
// under another criterion (flips<MaxMinEdgeWeight>) or another policy is
// compiled where it is used, as any template.
#pragma once

#include <metrica/geometry/model_or_facets.hpp>
#include <metrica/metrics/space.hpp>
#include <metrica/pipeline/compiled_policies.hpp>
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

// Where boundary vertices go: a CAD model's when one is given, else the
// start mesh's facets, chosen at run time (one instantiation for both).
using Geometries = PolicyList<ModelOrFacets>;

}  // namespace metrica

// The macros keep one instantiation a line, in the lists' order.
// clang-format off
// The standard stages of one (space, concurrency, geometry) triple: `kind`
// is `extern` for the declaration, empty for the definition.
#define METRICA_STANDARD_STAGES(kind, S, C, G)                                                                  \
  kind template OperatorStats collapse_edges<S, C, ShapeOnly, G>(Mesh&, const CollapseOptions&, const G&);     \
  kind template OperatorStats refine_edges<S, C, ShapeOnly, G>(Mesh&, const RefineOptions&, const G&);         \
  kind template OperatorStats refine_centroids<S, C, ShapeOnly, G>(Mesh&, const RefineOptions&, const G&);     \
  kind template OperatorStats reconnect<S, C, MinQuality, G>(Mesh&, const ReconnectOptions&, const G&);        \
  kind template OperatorStats smooth_vertices<S, C, MinQuality, G>(Mesh&, const SmoothOptions&, const G&);     \
  kind template OperatorStats swap_toward_model<S, C, G>(Mesh&, const BoundarySwapOptions&, const G&);         \
  kind template OperatorStats flip_interfaces<S, C, G>(Mesh&, const InterfaceFlipOptions&, const G&);          \
  kind template const AdaptReport& run_pipeline<Adapter<S, C, G>>(Adapter<S, C, G>&,                            \
                                                                  const Pipeline<Adapter<S, C, G>>&);
// What a precision changes in them: the metric-Delaunay flips (the
// centroid rule's), the standard pipeline that runs them, adapt.
#define METRICA_STANDARD_STAGES_OF_PRECISION(kind, S, P, C, G)                                                   \
  kind template OperatorStats reconnect<S, C, MetricDelaunay<P>, G>(Mesh&, const ReconnectOptions&, const G&); \
  kind template Pipeline<Adapter<S, C, G>> standard_pipeline<Adapter<S, C, G>, P>(const AdaptOptions&, bool);  \
  kind template AdaptReport adapt<S, P, C, G>(Mesh&, const AdaptOptions&, const AdaptInputs&, const G&);

// The triple at indices (space, concurrency, geometry) of the lists, with
// every precision compiled.
#define METRICA_STANDARD_STAGES_OF_TRIPLE(kind, S, C, G)                                                    \
  METRICA_STANDARD_STAGES(kind, S, C, G)                                                                  \
  METRICA_STANDARD_STAGES_OF_PRECISION(kind, S, ::metrica::Precisions::at<0>, C, G)                        \
  METRICA_FOR_EACH_OTHER_PRECISION(METRICA_STANDARD_STAGES_OF_PRECISION, kind, S, C, G)
#define METRICA_STANDARD_STAGES_AT(kind, s, c, g)                                                           \
  METRICA_STANDARD_STAGES_OF_TRIPLE(kind, ::metrica::Spaces::at<s>, ::metrica::Concurrencies::at<c>,        \
                                    ::metrica::Geometries::at<g>)
// clang-format on
