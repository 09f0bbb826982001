// What a pass works from besides its tuning: the metric new vertices
// take, where the mesh changed, and the edges already counted. The
// Adapter binds it (pipeline/adapter.hpp: its metric, the stage's epoch,
// its cycle's edge counts); a caller who runs an operation alone leaves
// it empty (interpolated metrics, the whole mesh, a fresh count).
#pragma once

#include <metrica/mesh.hpp>
#include <metrica/operators/metric_source.hpp>

namespace metrica {

struct OutOfBandEdges;  // edge_queue.hpp

struct PassScope {
  // When set (an analytic metric or a background), new and moved vertices
  // take the metric at their position instead of an interpolated one.
  MetricSource metric;
  // Only the items whose cavity changed since this epoch are tried (0:
  // all): an operation whose decision reads only its cavity would refuse
  // an unchanged one again.
  Mesh::Epoch changed_since = 0;
  // When set, edge work lists come from these edges where they can
  // (edges_beyond).
  const OutOfBandEdges* known = nullptr;
};

}  // namespace metrica
