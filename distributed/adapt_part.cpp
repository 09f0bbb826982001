#include <metrica/allocator.hpp>
#include <metrica/distributed/adapt_part.hpp>
#include <metrica/distributed/pinches.hpp>
#include <metrica/error.hpp>
#include <metrica/geometry/association.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/metrics/space.hpp>
#include <metrica/metrics/unit_band.hpp>
#include <metrica/operators/edge_buckets.hpp>
#include <metrica/pipeline/adapted_check.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace metrica::distributed {

namespace {

// The global id of each vertex of a part's mesh that had one before the
// round: the kept faces' vertices (they neither move nor go); -1 for a
// vertex the round made.
constexpr std::string_view kGlobalId = "global_id";

// Why a vertex of a round's mesh is unfinished (bits of a byte).
enum Unfinished : std::uint8_t {
  kOnEdgeOutOfBand = 1,      // on an edge out of [kShortEdge, kLongEdge]
  kOnPoorTet = 2,            // on a tet below kPoorTet
  kOnTetPoorAtKeptFace = 4,  // on a tet below kPoorAtKeptFace
  kOffModel = 8,             // a boundary vertex off the model
};
// What the next rounds must reach wherever the vertex is; what keeps an
// adaptation from ending.
constexpr std::uint8_t kMustReach = kOnPoorTet | kOffModel;
constexpr std::uint8_t kPoor = kOnPoorTet | kOnTetPoorAtKeptFace | kOffModel;

// The quality of a mesh's tets and edges; with `unfinished`, each vertex
// gets the Unfinished bits of its edges and tets. The edges come
// from the adaptation's edge buckets and are tested against the bands
// rather than measured (most need no root or logarithm); the mean ratios
// come from the quality cache when an adaptation in `space` left it
// filled. Measuring every edge and tet after a part's first round took
// 0.13 s of its 6.6 (1M tets on 2 ranks).
QualityTally tally(const Mesh& mesh, std::string_view space, std::vector<std::uint8_t>* unfinished) {
  return with_policy<Spaces>("metric space", space, [&]<class S>() {
    QualityTally q;
    const UnitBand finished{kShortEdge, kLongEdge};
    for_each_mesh_edge_bucket<Serial>(mesh, 1, [&](std::size_t, VertexId a, std::span<const VertexId> upper) {
      q.edges += std::int64_t(upper.size());
      for (VertexId b : upper) {
        q.edges_in_range += S::edge_length_in(mesh, a, b, kUnitBand);
        if (unfinished && !S::edge_length_in(mesh, a, b, finished))
          (*unfinished)[std::size_t(a)] |= kOnEdgeOutOfBand, (*unfinished)[std::size_t(b)] |= kOnEdgeOutOfBand;
      }
    });
    const bool cached = mesh.quality_cache_space() == S::name;
    for (TetId t = 0; t < mesh.tet_capacity(); ++t) {
      if (!mesh.tet_alive(t)) continue;
      const double r = cached ? cached_mean_ratio<S>(mesh, t) : S::mean_ratio(mesh, mesh.tet(t));
      ++q.tets;
      q.min_quality = std::min(q.min_quality, r);
      q.sum_quality += r;
      if (unfinished && r < kPoorAtKeptFace)
        for (VertexId v : mesh.tet(t))
          (*unfinished)[std::size_t(v)] |= r < kPoorTet ? kOnPoorTet | kOnTetPoorAtKeptFace : kOnTetPoorAtKeptFace;
    }
    return q;
  });
}

bool holds(const std::vector<FaceKey>& sorted, const FaceKey& k) {
  return std::binary_search(sorted.begin(), sorted.end(), k);
}

// Where the adapted tets meet what stays as it is.
struct ActiveBounds {
  std::vector<FaceKey> frozen;         // faces of active tets kept as they are (sorted): shared or against a kept tet
  std::vector<FaceKey> shared_active;  // the shared faces of active tets (sorted)
  // Per triangle of the part: a face of an active tet the adaptation may
  // change. One on a frozen face (an internal surface's, with a tet on
  // either side) stays in the part as it is: the part's mesh has that face
  // on its boundary, among the faces it keeps.
  std::vector<bool> triangle_active;
};

ActiveBounds active_bounds(const Part& part, const VertexIndex& index, const std::vector<bool>& active) {
  ActiveBounds b;
  // Every face asked about below has its three vertices on a kept tet, a
  // shared face or a triangle: the active tets' faces among those, sorted
  // (a band along the active region's boundary, not all its faces).
  const auto local = [&](GlobalId g) { return std::size_t(index.find(g)); };
  std::vector<bool> special(part.vertex_ids.size(), false), on_active(part.vertex_ids.size(), false);
  for (std::size_t t = 0; t < part.tets.size(); ++t)
    for (auto v : part.tets[t]) (active[t] ? on_active : special)[v] = true;
  for (const auto& k : part.shared_faces)
    for (GlobalId g : k) special[local(g)] = true;
  for (const auto& k : part.triangles)
    for (GlobalId g : k) special[local(g)] = true;
  std::vector<FaceKey> faces;
  for (std::size_t t = 0; t < part.tets.size(); ++t) {
    if (!active[t]) continue;
    const auto& v = part.tets[t];
    for (int f = 0; f < 4; ++f) {
      const auto& c = kTetFaces[f];
      if (special[v[std::size_t(c[0])]] && special[v[std::size_t(c[1])]] && special[v[std::size_t(c[2])]])
        faces.push_back(global_face(part, t, f));
    }
  }
  std::sort(faces.begin(), faces.end());
  // A face of a kept tet with its three vertices on active tets may be
  // one of theirs.
  for (std::size_t t = 0; t < part.tets.size(); ++t) {
    if (active[t]) continue;
    const auto& v = part.tets[t];
    for (int f = 0; f < 4; ++f) {
      const auto& c = kTetFaces[f];
      if (!on_active[v[std::size_t(c[0])]] || !on_active[v[std::size_t(c[1])]] || !on_active[v[std::size_t(c[2])]])
        continue;
      const auto key = global_face(part, t, f);
      if (holds(faces, key)) b.frozen.push_back(key);
    }
  }
  for (const auto& k : part.shared_faces)
    if (holds(faces, k)) b.shared_active.push_back(k);
  b.frozen.insert(b.frozen.end(), b.shared_active.begin(), b.shared_active.end());
  std::sort(b.frozen.begin(), b.frozen.end());
  b.frozen.erase(std::unique(b.frozen.begin(), b.frozen.end()), b.frozen.end());
  std::sort(b.shared_active.begin(), b.shared_active.end());
  b.triangle_active.resize(part.triangles.size());
  for (std::size_t i = 0; i < part.triangles.size(); ++i)
    b.triangle_active[i] = holds(faces, face_key(part.triangles[i])) && !holds(b.frozen, face_key(part.triangles[i]));
  return b;
}

// The round's tets as the content of a mesh file, numbered locally, with
// what the mesh needs besides: the metrics and model parameters of its
// vertices, and the kept faces' vertices' global ids.
struct RoundInput {
  io::MeshData data;
  std::vector<std::uint32_t> part_vertex;  // the part's vertex of each of data's
  std::vector<Sym6> metrics;               // none with an analytic metric
  std::vector<GeoParam> params;            // none without a model
  std::vector<std::pair<VertexId, GlobalId>> kept;
};

RoundInput round_input(const Part& part, const VertexIndex& index, const std::vector<bool>& active,
                       const ActiveBounds& bounds, const PartAdaptSettings& settings) {
  RoundInput in;
  std::vector<std::int64_t> local(part.vertex_ids.size(), -1);
  auto& data = in.data;
  auto number_local = [&](std::size_t v) {
    if (local[v] < 0) {
      local[v] = std::int64_t(in.part_vertex.size());
      in.part_vertex.push_back(std::uint32_t(v));
      data.vertices.push_back(part.points[v]);
    }
    return VertexId(local[v]);
  };
  auto number = [&](GlobalId g) { return number_local(std::size_t(index.find(g))); };
  for (std::size_t t = 0; t < part.tets.size(); ++t) {
    if (!active[t]) continue;
    TetVertices l;
    for (int c = 0; c < 4; ++c) l[std::size_t(c)] = number_local(part.tets[t][std::size_t(c)]);
    data.tets.push_back(l);
    data.tet_refs.push_back(part.tet_refs[t]);
  }
  auto local_face = [&](const std::array<GlobalId, 3>& k) {
    return TriangleVertices{number(k[0]), number(k[1]), number(k[2])};
  };
  for (std::size_t i = 0; i < part.triangles.size(); ++i) {
    if (!bounds.triangle_active[i]) continue;
    data.triangles.push_back(local_face(part.triangles[i]));
    data.triangle_refs.push_back(part.triangle_refs[i]);
  }
  for (const auto& k : bounds.frozen) {
    data.required_triangles.push_back(std::uint32_t(data.triangles.size()));
    data.triangles.push_back(local_face(k));
    data.triangle_refs.push_back(kPartFaceId);
  }
  if (!settings.exact) in.metrics.reserve(in.part_vertex.size());
  if (settings.model) in.params.reserve(in.part_vertex.size());
  for (auto v : in.part_vertex) {
    if (!settings.exact) in.metrics.push_back(part.metrics[v]);
    if (settings.model) in.params.push_back(part.geo[v]);
  }
  for (const auto& k : bounds.frozen)
    for (GlobalId g : k) in.kept.emplace_back(VertexId(local[std::size_t(index.find(g))]), g);
  return in;
}

// The active tets' records, their triangles and the vertices only they
// hold leave the part: the adapted tets take their place.
void drop_active_records(Part& part, const std::vector<bool>& active, const ActiveBounds& bounds) {
  std::vector<bool> kept_tets(part.tets.size());
  for (std::size_t t = 0; t < kept_tets.size(); ++t) kept_tets[t] = !active[t];
  keep_tets(part, kept_tets);
  part.focus.clear();
  std::vector<bool> used(part.vertex_ids.size(), false);
  for (const auto& t : part.tets)
    for (auto v : t) used[v] = true;
  keep_vertices(part, used);
  std::vector<bool> untouched(part.triangles.size());
  for (std::size_t i = 0; i < untouched.size(); ++i) untouched[i] = !bounds.triangle_active[i];
  keep_triangles(part, untouched);
  release_freed_memory();
}

// The round's mesh: built with the cut's faces as they are, its metric,
// its vertices' model parameters, and the kept faces' vertices' global ids
// as the attribute kGlobalId. Takes in.data, in.metrics and in.params.
Mesh round_mesh(RoundInput& in, const PartAdaptSettings& settings, int rank) {
  BuildOptions bo;
  bo.default_surface_id = settings.default_surface_id;
  bo.ridge_angle = kNoRidgeSplit;  // the input's surfaces as given; the cut's faces keep their own id
  bo.source = fmt::format("part {}", rank);
  Mesh mesh = build_mesh(in.data, bo);
  in.data = io::MeshData{};
  release_freed_memory();  // the build's work under the adaptation's peak
  if (settings.exact) {
    assign_metric(mesh, *settings.exact);
  } else {
    assign_metric(mesh, in.metrics);
    in.metrics = {};
  }
  if (settings.model) {
    // A vertex at a model vertex is a corner whatever the faces around it.
    mesh.enable_geo_params();
    bool model_vertex = false;
    for (std::size_t l = 0; l < in.params.size(); ++l) {
      mesh.set_geo_param(VertexId(l), in.params[l]);
      model_vertex |= in.params[l].dim == 0;
    }
    in.params = {};
    if (model_vertex) mesh.classify();
  }
  if (settings.keep_surface) mesh.keep_surface();
  auto& global = mesh.add_vertex_attribute<GlobalId>(std::string(kGlobalId), -1);
  for (const auto& [l, g] : in.kept) global[l] = g;
  in.kept = {};
  return mesh;
}

// A round's mesh measured: its quality, the Unfinished bits of each
// vertex (an edge out of the band counts on a kept face, kMustReach
// anywhere) and its boundary vertices off the model. A vertex the round
// left off the model (its closing could not place it) is unfinished: the
// next round, with it inside a part, projects it again; the output is
// written only with every vertex on the model.
struct RoundFigures {
  QualityTally quality;
  std::vector<std::uint8_t> unfinished;
  std::int64_t off_model = 0;
  std::vector<GlobalId> poor;  // the global ids of the vertices with kPoor (before a keep_worst round)
};

RoundFigures round_figures(const Mesh& mesh, const PartAdaptSettings& settings) {
  RoundFigures f;
  f.unfinished.assign(std::size_t(mesh.vertex_capacity()), 0);
  f.quality = tally(mesh, settings.policies.space, &f.unfinished);
  if (settings.model)
    for (VertexId v : vertices_off_model(mesh, *settings.model, kOnModel, kPartFaceId)) {
      f.unfinished[std::size_t(v)] |= kOffModel;
      ++f.off_model;
    }
  return f;
}

// The adapted mesh as part records (its vertices numbered as in `records`,
// the kept faces' vertices with their global ids, the new ones -1 for
// now), and what the next rounds need of it.
struct Adapted {
  Part records;
  std::int64_t fresh = 0;
  std::vector<std::uint32_t> fresh_unfinished;  // new vertices with kMustReach (local numbers)
  std::vector<std::uint32_t> fresh_poor;        // new vertices with kPoor (local numbers)
  std::vector<FaceKey> faces_kept;              // faces whose vertices were all kept
};

// Frees the mesh once its content is taken. `unfinished` holds each
// vertex's Unfinished bits; the kept vertices among them join the
// result's lists.
Adapted adapted_records(std::optional<Mesh>& built, const std::vector<std::uint8_t>& unfinished,
                        const PartAdaptSettings& settings, PartAdaptResult& result) {
  Adapted a;
  Part& adapted = a.records;
  const Mesh& mesh = *built;
  io::MeshData out = extract_mesh_data(mesh);
  // Sized once: grown by doubling beside the mesh and its file content,
  // the copies set a rank's peak.
  if (!settings.exact) adapted.metrics.reserve(mesh.num_vertices());
  if (settings.model) adapted.geo.reserve(mesh.num_vertices());
  // out.vertices are the live vertices in id order.
  std::vector<GlobalId> ids;
  std::vector<std::uint8_t> why;
  ids.reserve(out.vertices.size());
  why.reserve(out.vertices.size());
  const auto& global = *mesh.find_vertex_attribute<GlobalId>(kGlobalId);
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
    if (!mesh.vertex_alive(v)) continue;
    ids.push_back(global[v]), why.push_back(unfinished[std::size_t(v)]);
    if (!settings.exact) adapted.metrics.push_back(mesh.metric(v));
    if (settings.model) adapted.geo.push_back(mesh.geo_param(v));
  }
  built.reset();  // the file content is all that is needed now
  for (std::size_t v = 0; v < ids.size(); ++v) {
    if (ids[v] >= 0) {
      if (why[v]) result.kept_vertices.push_back(ids[v]);
      if (why[v] & kPoor) result.poor_vertices.push_back(ids[v]);
    } else {
      ++a.fresh;
      if (why[v] & kMustReach) a.fresh_unfinished.push_back(std::uint32_t(v));
      if (why[v] & kPoor) a.fresh_poor.push_back(std::uint32_t(v));
    }
  }
  for (const auto& l : out.triangles)
    if (ids[l[0]] >= 0 && ids[l[1]] >= 0 && ids[l[2]] >= 0)
      a.faces_kept.push_back(face_key(ids[l[0]], ids[l[1]], ids[l[2]]));
  adapted.vertex_ids = std::move(ids);
  adapted.points = std::move(out.vertices);
  adapted.tets.reserve(out.tets.size());
  for (const auto& l : out.tets) adapted.tets.push_back({l[0], l[1], l[2], l[3]});
  out.tets = {};
  adapted.tet_refs = std::move(out.tet_refs);
  // The triangles by local number until the new vertices have their ids.
  for (std::size_t f = 0; f < out.triangles.size(); ++f) {
    if (out.triangle_refs[f] == kPartFaceId) continue;
    const auto& l = out.triangles[f];
    adapted.triangles.push_back({GlobalId(l[0]), GlobalId(l[1]), GlobalId(l[2])});
    adapted.triangle_refs.push_back(out.triangle_refs[f]);
  }
  return a;
}

// The tets the round kept, the vertices only they hold and their
// triangles stay in the part, the adapted ones join them (the kept faces'
// vertices come back with the adapted tets: the kept tets name those
// copies, after the part's own vertices).
void join_adapted(Part& part, Part& adapted) {
  {
    const VertexIndex have(adapted.vertex_ids);
    const std::size_t nv = part.vertex_ids.size();
    std::vector<bool> apart(nv);
    std::vector<std::int64_t> copy(nv);  // the vertex's place in `adapted`, -1: none
    std::size_t own = 0;
    for (std::size_t v = 0; v < nv; ++v)
      copy[v] = have.find(part.vertex_ids[v]), apart[v] = copy[v] < 0, own += apart[v];
    std::vector<std::uint32_t> place(nv);
    std::uint32_t next = 0;
    for (std::size_t v = 0; v < nv; ++v) place[v] = apart[v] ? next++ : std::uint32_t(own + std::size_t(copy[v]));
    for (auto& t : part.tets)
      for (auto& v : t) v = place[v];
    keep_vertex_records(part, apart);
    for (auto& t : adapted.tets)
      for (auto& v : t) v += std::uint32_t(own);
  }
  const auto append = [](auto& to, auto& from) {
    to.reserve(to.size() + from.size());  // once, to the size (a doubling would hold both copies)
    to.insert(to.end(), from.begin(), from.end());
    from = {};
  };
  append(part.vertex_ids, adapted.vertex_ids);
  append(part.points, adapted.points);
  append(part.metrics, adapted.metrics);
  append(part.geo, adapted.geo);
  append(part.tets, adapted.tets);
  append(part.tet_refs, adapted.tet_refs);
  append(part.triangles, adapted.triangles);
  append(part.triangle_refs, adapted.triangle_refs);
}

}  // namespace

PartAdaptResult adapt_part(const Comm& comm, Part& part, const PartAdaptSettings& settings, GlobalId& next_id) {
  PartAdaptResult result;
  Adapted adapted;
  ActiveBounds bounds;
  bool changed = false;  // this rank adapted some tets
  comm.step([&] {
    if (part.tets.empty()) return;
    Stopwatch clock;
    std::vector<bool> wanted(part.tets.size(), true);
    if (!part.focus.empty())
      for (std::size_t t = 0; t < wanted.size(); ++t) wanted[t] = part.focus[t] != 0;
    const std::vector<bool> active = adaptable_tets(part, wanted);
    for (std::size_t t = 0; t < part.tets.size(); ++t) {
      result.adapted += active[t];
      if (wanted[t] && !active[t]) {
        ++result.kept_out;
        const auto g = global_tet(part, t);
        result.kept_vertices.insert(result.kept_vertices.end(), g.begin(), g.end());
        result.held.insert(result.held.end(), g.begin(), g.end());
      }
    }
    RoundInput in;
    {
      const VertexIndex index(part.vertex_ids);
      bounds = active_bounds(part, index, active);
      for (const auto& k : bounds.frozen) result.held.insert(result.held.end(), k.begin(), k.end());
      std::sort(result.held.begin(), result.held.end());
      result.held.erase(std::unique(result.held.begin(), result.held.end()), result.held.end());
      in = round_input(part, index, active, bounds, settings);
    }
    if (in.data.tets.empty()) return;
    changed = true;
    // The active tets' records go once the adapted tets are sure to take
    // their place: before the mesh is built (their content is in `in`),
    // or with keep_worst once the round is taken.
    if (!settings.keep_worst) drop_active_records(part, active, bounds);
    std::optional<Mesh> built(round_mesh(in, settings, comm.rank()));
    Mesh& mesh = *built;
    result.volume_before = mesh.volume();
    // With keep_worst, the tets as they came.
    RoundFigures before;
    if (settings.keep_worst) {
      before = round_figures(mesh, settings);
      // The mesh's vertices are in.part_vertex's, in order.
      for (std::size_t l = 0; l < in.part_vertex.size(); ++l)
        if (before.unfinished[l] & kPoor) before.poor.push_back(part.vertex_ids[in.part_vertex[l]]);
      before.unfinished = {};
    }
    in.part_vertex = {};
    AdaptInputs inputs;
    inputs.metric = settings.exact;
    inputs.background = settings.background;
    inputs.model = settings.model;
    adapt_by_name(mesh, settings.options, settings.policies, inputs);
    // The passes' freed blocks back to the kernel before the file content
    // is made beside the mesh: kept, they set a rank's peak (4.3M tets on
    // 2 ranks: 277 MiB, 270 without).
    release_freed_memory();
    // Valid, with the volume checked over all parts by the caller.
    require_adapted(mesh, nullptr, result.volume_before, 1e300);
    result.volume_after = mesh.volume();
    RoundFigures after = round_figures(mesh, settings);
    result.quality = after.quality;
    result.off_model = after.off_model;
    if (settings.keep_worst) {
      // A round that leaves a tet poorer than the poorest it was given, and
      // below kPoorAtKeptFace, is undone on this part: its tets stay as they
      // were, their poor tets unfinished. A round on a mesh adapted before
      // risks poor tets against the faces its cut keeps, and the last
      // round's stayed in the output (UGAWG polar-1 on 4 ranks, 6 focus
      // layers: min Q 0.171 against 0.388 with this).
      if (after.quality.min_quality < before.quality.min_quality && after.quality.min_quality < kPoorAtKeptFace) {
        result.undone = true;
        result.quality = before.quality;
        result.off_model = before.off_model;
        result.volume_after = result.volume_before;
        result.kept_vertices.insert(result.kept_vertices.end(), before.poor.begin(), before.poor.end());
        result.poor_vertices = before.poor;
        changed = false;
        result.seconds = clock.seconds();
        return;
      }
      drop_active_records(part, active, bounds);
    }
    adapted = adapted_records(built, after.unfinished, settings, result);
    result.seconds = clock.seconds();
  });
  const std::int64_t base = next_id + comm.exclusive_scan(adapted.fresh);
  next_id += comm.sum(adapted.fresh);
  if (!changed) {
    comm.step([] {});  // the others' check below
    return result;
  }
  Part& records = adapted.records;
  GlobalId at = base;
  for (auto& g : records.vertex_ids)
    if (g < 0) g = at++;
  for (auto v : adapted.fresh_unfinished) result.kept_vertices.push_back(records.vertex_ids[v]);
  for (auto v : adapted.fresh_poor) result.poor_vertices.push_back(records.vertex_ids[v]);
  for (auto& f : records.triangles)
    for (auto& v : f) v = records.vertex_ids[std::size_t(v)];
  join_adapted(part, records);
  // The faces between parts must come out as they went in: the rank
  // across relies on them.
  comm.step([&] {
    auto& kept = adapted.faces_kept;
    std::sort(kept.begin(), kept.end());
    std::size_t lost = 0;
    for (const auto& k : bounds.shared_active) lost += !holds(kept, k);
    if (lost > 0)
      throw std::runtime_error(fmt::format("{} of the {} faces kept between parts changed in the adaptation", lost,
                                           bounds.shared_active.size()));
  });
  return result;
}

QualityTally part_quality(const Part& part, const PartAdaptSettings& settings) {
  QualityTally all;
  std::vector<std::int64_t> local(part.vertex_ids.size(), -1);
  for (std::size_t begin = 0; begin < part.tets.size(); begin += kQualityPieceTets) {
    const std::size_t end = std::min(part.tets.size(), begin + kQualityPieceTets);
    io::MeshData data;
    std::vector<Sym6> metrics;
    std::vector<std::size_t> numbered;
    const auto number = [&](std::size_t v) {
      if (local[v] < 0) {
        local[v] = std::int64_t(data.vertices.size());
        numbered.push_back(v);
        data.vertices.push_back(part.points[v]);
        if (!part.metrics.empty()) metrics.push_back(part.metrics[v]);
      }
      return VertexId(local[v]);
    };
    for (std::size_t t = begin; t < end; ++t) {
      const auto& g = part.tets[t];
      data.tets.push_back({number(g[0]), number(g[1]), number(g[2]), number(g[3])});
      data.tet_refs.push_back(part.tet_refs[t]);
    }
    for (auto v : numbered) local[v] = -1;
    BuildOptions bo;
    bo.default_surface_id = settings.default_surface_id;
    bo.ridge_angle = kNoRidgeSplit;  // the cut's faces keep their own id
    bo.untagged_expected = true;
    Mesh mesh = build_mesh(data, bo);
    data = io::MeshData{};
    release_freed_memory();
    if (settings.exact)
      assign_metric(mesh, *settings.exact);
    else
      assign_metric(mesh, metrics);
    const auto piece = tally(mesh, settings.policies.space, nullptr);
    all.edges += piece.edges;
    all.edges_in_range += piece.edges_in_range;
    all.tets += piece.tets;
    all.min_quality = std::min(all.min_quality, piece.min_quality);
    all.sum_quality += piece.sum_quality;
  }
  return all;
}

}  // namespace metrica::distributed
