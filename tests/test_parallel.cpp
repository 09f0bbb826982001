// The Speculative policy: owner-word locks (all or nothing), the rounds of
// a work list (every item runs exactly once, conflicts replayed), the
// threads' allocation pools (unique ids, counts, growth between rounds),
// and whole adaptations on 1, 2 and 8 threads (8 on a 2-core machine
// forces interleavings): valid, the quality of the serial run, no
// conflict on one thread. Serial runs are the same to the bit.
#include "operator_test_support.hpp"

#include <metrica/allocator.hpp>
#include <metrica/box.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/mesh_edges.hpp>
#include <metrica/operators/collapse.hpp>
#include <metrica/operators/edge_buckets.hpp>
#include <metrica/operators/edge_queue.hpp>
#include <metrica/operators/refine_edges.hpp>
#include <metrica/part_runner.hpp>
#include <metrica/pipeline/adapt.hpp>
#include <metrica/pipeline/adapt_dispatch.hpp>
#include <metrica/policies/speculative.hpp>
#include <metrica/policies/threads.hpp>
#include <metrica/validate.hpp>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <iterator>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

using namespace metrica;
using namespace metrica::test;

namespace {

// A random anisotropic metric (ratio `ratio`, seed `seed`) at each vertex,
// scaled by base + slope x: sizes graded along x.
void assign_graded_metric(Mesh& mesh, std::uint64_t seed, double ratio, double base, double slope) {
  auto r = rng(seed);
  std::vector<Sym6> field(mesh.vertex_capacity());
  for (VertexId v = 0; v < mesh.vertex_capacity(); ++v) {
    const Sym6 m = random_metric(r, ratio);
    const double s = base + slope * mesh.point(v).x();
    field[v] = Sym6{m[0] * s, m[1] * s, m[2] * s, m[3] * s, m[4] * s, m[5] * s};
  }
  assign_metric(mesh, field);
}

struct Adapted {
  Mesh mesh;
  AdaptReport report;
};

// The 4x4x4 cube adapted to small_linear by `run(mesh, options)`.
template <class Run>
Adapted adapt_linear_by(Run&& run) {
  Adapted a{small_linear_box(), {}};
  const MetricFunction metric = small_linear;
  a.report = run(a.mesh, AdaptOptions{}, AdaptInputs{.metric = &metric});
  return a;
}

Adapted adapt_linear(const std::string& c) {
  return adapt_linear_by([c](Mesh& mesh, const AdaptOptions& o, const AdaptInputs& in) {
    return adapt_by_name(mesh, o, {.concurrency = c}, in);
  });
}

// The pipeline with every list shared out however short (by default
// Speculative runs lists under 8192 items on one thread, which at this
// size is all of them): the parallel path under test.
Adapted adapt_linear_shared() {
  return adapt_linear_by([](Mesh& mesh, const AdaptOptions& o, const AdaptInputs& in) {
    const SpeculativeScope shared({.small_list = 0});
    return adapt<LogEuclidean, Filtered, Speculative>(mesh, o, in);
  });
}

std::size_t total_conflicts(const AdaptReport& r) { return r.ops.total().conflicts; }

// The three worst tets by their true (not cached) mean ratio, with their
// vertices' classes and their boundary faces' surface ids, and the min Q
// after each cycle: what a failing quality check prints.
std::string worst_tets(const Adapted& a) {
  std::vector<std::pair<double, TetId>> q;
  for (TetId t = 0; t < a.mesh.tet_capacity(); ++t)
    if (a.mesh.tet_alive(t)) q.emplace_back(LogEuclidean::mean_ratio(a.mesh, a.mesh.tet(t)), t);
  std::partial_sort(q.begin(), q.begin() + std::min<std::ptrdiff_t>(3, std::ssize(q)), q.end());
  std::ostringstream out;
  out << "cycles' min Q:";
  for (const auto& c : a.report.cycles) out << ' ' << c.min_quality;
  for (std::size_t i = 0; i < std::min<std::size_t>(3, q.size()); ++i) {
    const TetId t = q[i].second;
    out << "\n  tet " << t << " Q " << q[i].first << " (cached " << a.mesh.cached_quality(t) << "), vertices";
    for (VertexId v : a.mesh.tet(t)) out << ' ' << v << ':' << to_string(a.mesh.vertex_class(v));
    out << ", boundary faces";
    for (int f = 0; f < 4; ++f)
      if (!a.mesh.neighbour(t, f).valid()) out << ' ' << f << ":surface " << a.mesh.surface_id(t, f);
  }
  return out.str();
}

// Restores the thread count a test changed.
struct ThreadCountGuard {
  int saved = thread_count();
  ~ThreadCountGuard() { set_thread_count(saved); }
};

// The serial executor's adaptation of the small cube; where the build
// compiles the speculative pipeline only (scripts/tsan), Speculative on one
// thread, which the Release build's tests hold to the serial one.
Adapted adapt_linear_serial() {
  if constexpr (METRICA_SPECULATIVE_ONLY) {
    ThreadCountGuard guard;
    set_thread_count(1);
    return adapt_linear("speculative");
  } else {
    return adapt_linear("serial");
  }
}

}  // namespace

TEST_SUITE("parallel") {
  TEST_CASE("owner words: a cavity is acquired whole or not at all") {
    Speculative::OwnerTable owners;
    owners.resize(16);
    Speculative::Locks a(owners.data(), 1), b(owners.data(), 2);
    CHECK(a.acquire({1, 2, 3}));
    CHECK(a.acquire({3, 4}));  // 3 is already a's: skipped
    CHECK(a.held() == 4);
    CHECK_FALSE(b.acquire({5, 6, 4}));  // 4 is a's: b keeps nothing
    CHECK(b.held() == 0);
    CHECK(owners.data()[5].load() == 0);
    CHECK(owners.data()[6].load() == 0);
    a.release();
    CHECK(b.acquire({5, 6, 4}));
    CHECK(owners.data()[4].load() == 2);
    // The only thread of a pass takes anything and writes no word.
    Speculative::Locks alone(owners.data(), 1, true);
    CHECK(alone.acquire({4, 7}));
    CHECK(alone.held() == 0);
    CHECK(owners.data()[4].load() == 2);
    CHECK(owners.data()[7].load() == 0);
  }

  TEST_CASE("every item of a work list runs to the end exactly once, conflicts replayed in later rounds") {
    Mesh mesh = make_box({.nx = 2, .ny = 2, .nz = 2});
    std::vector<VertexId> items(2000);
    for (std::size_t i = 0; i < items.size(); ++i) items[i] = static_cast<VertexId>(i % mesh.num_vertices());
    std::vector<std::atomic<int>> done(items.size()), attempts(items.size());
    std::vector<std::uint32_t> index(items.size());
    for (std::size_t i = 0; i < items.size(); ++i) index[i] = static_cast<std::uint32_t>(i);
    // Each item locks its vertex and a neighbour id; a third of the items
    // report a conflict on their first attempt whatever happens.
    auto work = [&](std::uint32_t i, int, SpeculativeLocks& locks) {
      const int attempt = attempts[i]++;
      const VertexId v = items[i], w = (v + 1) % static_cast<VertexId>(mesh.num_vertices());
      if (!locks.acquire({v, w}) || (i % 3 == 0 && attempt == 0)) return Attempt::conflict;
      ++done[i];
      return Attempt::done;
    };
    for (int threads : {1, 2, 8}) {
      CAPTURE(threads);
      for (auto& d : done) d = 0;
      for (auto& a : attempts) a = 0;
      const SpeculativeScope pinned({.threads = threads, .small_list = 0});
      const PassTally tally = Speculative::for_each(mesh, std::span<const std::uint32_t>(index), PassRoom{}, work);
      for (std::size_t i = 0; i < items.size(); ++i) REQUIRE(done[i] == 1);
      CHECK(tally.conflicts >= (items.size() + 2) / 3);
      CHECK(tally.replays == tally.conflicts);
      CHECK(tally.rounds >= 2);
      require_valid(mesh, 1.0);  // nothing written, the reserve handed back
    }
  }

  TEST_CASE("allocation pools: threads create unique ids, the counts add up, the reserve grows between rounds") {
    Mesh mesh = make_box({.nx = 2, .ny = 2, .nz = 2});
    const std::size_t v0 = mesh.num_vertices(), t0 = mesh.num_tets();
    // More items than the reserve's first size (a tenth of them plus two
    // chunks per thread).
    std::vector<std::uint32_t> index(30000);
    for (std::size_t i = 0; i < index.size(); ++i) index[i] = static_cast<std::uint32_t>(i);
    std::vector<VertexId> made_v(index.size(), kNoId);
    std::vector<TetId> made_t(index.size(), kNoId);
    // Each item makes one vertex and two tets and removes one of them (the
    // tets are not linked into the mesh: only the allocation is tested).
    auto work = [&](std::uint32_t i, int, SpeculativeLocks&) {
      made_v[i] = mesh.add_vertex(Point(2.0, 2.0, 2.0));
      const TetId keep = mesh.add_tet({kNoId - 1, kNoId - 1, kNoId - 1, kNoId - 1});
      mesh.remove_tet(mesh.add_tet({kNoId - 1, kNoId - 1, kNoId - 1, kNoId - 1}));
      made_t[i] = keep;
      return Attempt::done;
    };
    // Room for a tenth of the items: the rest waits for growth.
    const PassRoom room{.max_vertices = 1, .max_tets = 2, .vertices_per_item = 0.1, .tets_per_item = 0.1};
    const PassTally tally = SpeculativeOn<8>::for_each(mesh, std::span<const std::uint32_t>(index), room, work);
    CHECK(tally.conflicts == 0);
    CHECK(tally.rounds >= 2);  // items waited for the reserve to grow
    CHECK(std::set<VertexId>(made_v.begin(), made_v.end()).size() == index.size());
    CHECK(std::set<TetId>(made_t.begin(), made_t.end()).size() == index.size());
    CHECK(mesh.num_vertices() == v0 + index.size());
    CHECK(mesh.num_tets() == t0 + index.size());
    for (VertexId v : made_v) REQUIRE(mesh.vertex_alive(v));
    for (TetId t : made_t) REQUIRE(mesh.tet_alive(t));
  }

  TEST_CASE("allocation pools: a pass that throws hands every id back, its changes counted, one source at a time") {
    Mesh mesh = make_box({.nx = 2, .ny = 2, .nz = 2});
    const std::size_t v0 = mesh.num_vertices(), t0 = mesh.num_tets(), cap = mesh.vertex_capacity();
    const std::uint64_t changes0 = mesh.vertex_changes();
    std::vector<std::uint32_t> index(20000);
    for (std::size_t i = 0; i < index.size(); ++i) index[i] = static_cast<std::uint32_t>(i);
    // Every item makes a vertex and removes it; item 15000 throws.
    auto work = [&](std::uint32_t i, int, SpeculativeLocks&) {
      mesh.remove_vertex(mesh.add_vertex(Point(2.0, 2.0, 2.0)));
      if (i == 15000) throw std::runtime_error("item 15000");
      return Attempt::done;
    };
    const PassRoom room{.max_vertices = 1, .max_tets = 0, .vertices_per_item = 0.5};
    CHECK_THROWS_WITH(SpeculativeOn<8>::for_each(mesh, std::span<const std::uint32_t>(index), room, work),
                      "item 15000");
    CHECK(mesh.num_vertices() == v0);
    CHECK(mesh.num_tets() == t0);
    CHECK(mesh.vertex_changes() > changes0);
    CHECK((mesh.vertex_changes() - changes0) % 2 == 0);  // each made and removed
    // Detached: the mesh allocates from its free lists (which got the room back).
    const VertexId v = mesh.add_vertex(Point(0.5, 0.5, 0.5));
    CHECK(v >= cap);
    CHECK(mesh.vertex_capacity() > cap);
    mesh.remove_vertex(v);
    {
      ParallelIds ids(mesh, 1, 0, 0, PartRunner{});
      CHECK_THROWS_AS(ParallelIds(mesh, 1, 0, 0, PartRunner{}), std::logic_error);
    }
    require_valid(mesh, 1.0);
  }

  TEST_CASE("the policies' sort orders a work list as std::sort does, on 1, 2, 3 and 8 threads") {
    // Long enough for the parallel slices and merges (3 threads: a merge
    // round with an odd slice left over).
    std::mt19937_64 r(5);
    std::vector<std::uint64_t> keys(100000);
    for (auto& k : keys) k = r() % 50000;  // repeats
    auto expect = keys;
    std::sort(expect.begin(), expect.end());
    auto serial = keys;
    Serial::sort(serial.begin(), serial.end(), std::less<std::uint64_t>{});
    CHECK(serial == expect);
    auto check = [&](auto policy) {
      auto got = keys;
      decltype(policy)::sort(got.begin(), got.end(), std::less<std::uint64_t>{});
      CHECK(got == expect);
    };
    check(SpeculativeOn<1>{});
    check(SpeculativeOn<2>{});
    check(SpeculativeOn<3>{});
    check(SpeculativeOn<8>{});
  }

  TEST_CASE("collect on 2, 3 and 8 threads lists what one thread lists, in the order of i; errors reach the caller") {
    // Items at irregular places, some twice, more in the last part (where
    // a pass's new tets sit), and blocks that end mid-run of items.
    auto f = [](std::size_t i, std::vector<std::uint32_t>& out) {
      if (i % 7 == 0 || i > 90000) out.push_back(static_cast<std::uint32_t>(i));
      if (i % 1000 < 3) out.push_back(static_cast<std::uint32_t>(i + 1));
    };
    const std::size_t n = 100003;
    const auto expect = Serial::collect<std::uint32_t>(n, f);
    REQUIRE(expect.size() > 20000);
    CHECK(SpeculativeOn<2>::collect<std::uint32_t>(n, f) == expect);
    CHECK(SpeculativeOn<3>::collect<std::uint32_t>(n, f) == expect);
    CHECK(SpeculativeOn<8>::collect<std::uint32_t>(n, f) == expect);
    auto fails = [](std::size_t i, std::vector<std::uint32_t>&) {
      if (i == 77777) throw std::runtime_error("item 77777");
    };
    CHECK_THROWS_WITH(SpeculativeOn<2>::collect<std::uint32_t>(n, fails), "item 77777");
  }

  TEST_CASE("ASCII outputs formatted on 2 and 8 threads and on 3 reversed parts: the bytes of one thread") {
    // Enough rows for several chunks and batches of chunks in each keyword.
    io::MeshData m;
    m.version = 2;
    auto r = rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const std::uint32_t n = 150001;  // 10 chunks of rows: 2 batches on 2 threads
    for (std::uint32_t i = 0; i < n; ++i) {
      m.vertices.push_back(draw_point(u, r));
      m.vertex_refs.push_back(static_cast<int>(i % 5));
      m.tets.push_back({i, (i + 1) % n, (i + 2) % n, (i + 3) % n});
      m.tet_refs.push_back(static_cast<int>(i % 3));
    }
    for (std::uint32_t i = 0; i < 40000; ++i) m.triangles.push_back({i, i + 1, i + 2});
    m.triangle_refs.assign(m.triangles.size(), 1);
    m.corners = {0, 5, 17};
    io::SolData sol;
    sol.count = n;
    sol.types = {io::SolType::sym_matrix};
    for (std::size_t i = 0; i < n * 6; ++i) sol.values.push_back(u(r));
    const PartRunner reversed = reversed_parts(3);
    TempDir dir;
    auto bytes_of = [](const std::string& path) {
      std::ifstream in(path, std::ios::binary);
      return std::string(std::istreambuf_iterator<char>(in), {});
    };
    // The versions differ in the numbers' width only: under ThreadSanitizer
    // one of them checks the parts' writes.
    const std::vector<int> versions = METRICA_TSAN ? std::vector<int>{2} : std::vector<int>{1, 2};
    // The reversed parts run on one thread: nothing for ThreadSanitizer.
    std::vector<PartRunner> runs{part_runner<SpeculativeOn<2>>(1 << 20), part_runner<SpeculativeOn<8>>(1 << 20)};
    if (!METRICA_TSAN) runs.push_back(reversed);
    for (int version : versions) {
      CAPTURE(version);
      const std::string mesh_text = io::format_mesh(m, io::Encoding::ascii, version);
      const std::string sol_text = io::format_sol(sol, io::Encoding::ascii, version);
      REQUIRE(mesh_text.size() > (std::size_t{4} << 20));
      for (const PartRunner& run : runs) {
        CAPTURE(run.parts);
        CHECK(io::format_mesh(m, io::Encoding::ascii, version, run) == mesh_text);
        CHECK(io::format_sol(sol, io::Encoding::ascii, version, run) == sol_text);
        io::write_meshb(dir / "m.mesh", m, version, run);
        io::write_sol(dir / "s.sol", sol, version, run);
        CHECK(bytes_of(dir / "m.mesh") == mesh_text);
        CHECK(bytes_of(dir / "s.sol") == sol_text);
      }
    }
  }

  TEST_CASE("validate on 2 and 8 threads and on 3 reversed parts: the report of one thread") {
    auto mesh = make_box({.nx = 24, .ny = 24, .nz = 24});
    // Vertices pushed through their balls (orientation) and neighbour
    // slots that do not point back (adjacency), all over the arrays.
    for (VertexId v = 0; v < mesh.vertex_capacity(); v += 997)
      if (mesh.vertex_class(v) == VertexClass::interior) mesh.point(v) += Point(0.3, 0.2, 0.1);
    for (TetId t = 5; t < mesh.tet_capacity(); t += 4999)
      for (int f = 0; f < 4; ++f)
        if (mesh.neighbour(t, f).valid()) {
          mesh.set_neighbour(t, f, FaceRef(t == 5 ? 6 : 5, 0));
          break;
        }
    const PartRunner reversed = reversed_parts(3);
    for (std::size_t cap : {3, 1000}) {
      const ValidationReport one = mesh.validate({.max_messages_per_check = cap});
      REQUIRE(one.count("orientation") > 3);
      REQUIRE(one.count("adjacency") > 3);
      for (const PartRunner& run :
           {part_runner<SpeculativeOn<2>>(1 << 20), reversed, part_runner<SpeculativeOn<8>>(1 << 20)}) {
        const ValidationReport parts = mesh.validate({.max_messages_per_check = cap, .run = run});
        CHECK(parts.counts() == one.counts());
        CHECK(parts.to_string() == one.to_string());
      }
    }
  }

  TEST_CASE("grow_array on 2 and 8 threads and on 3 reversed parts: old elements kept, new ones filled") {
    const PartRunner reversed = reversed_parts(3);
    for (const PartRunner& run :
         {PartRunner{}, part_runner<SpeculativeOn<2>>(1 << 20), reversed, part_runner<SpeculativeOn<8>>(1 << 20)}) {
      MeshArray<std::uint32_t> a;
      for (std::uint32_t i = 0; i < 10001; ++i) a.push_back(3 * i);
      a.shrink_to_fit();
      grow_array(a, 25000, 7u, 30000, run);  // reallocates
      REQUIRE(a.size() == 25000);
      CHECK(a.capacity() >= 30000);
      grow_array(a, 26003, 9u, 0, run);  // within the capacity
      grow_array(a, 100, 5u, 0, run);    // never shrinks
      REQUIRE(a.size() == 26003);
      std::size_t right = 0;
      for (std::size_t i = 0; i < a.size(); ++i) right += a[i] == (i < 10001 ? 3 * i : i < 25000 ? 7u : 9u);
      CHECK(right == a.size());
    }
  }

  TEST_CASE("grow_array across the large-block size: elements kept and filled, large blocks on 2 MiB boundaries") {
    // The adjacency's element: trivially copyable with a member
    // initialiser, which MeshArray's resize leaves unwritten
    // (mesh_array.hpp); grow_array's fill must set every new one.
    using Adjacency = std::array<FaceRef, 4>;
    static_assert(sizeof(Adjacency) * 100000 < kLargeBlock && sizeof(Adjacency) * 1000000 > kLargeBlock);
    for (const PartRunner& run : {PartRunner{}, part_runner<SpeculativeOn<2>>(1 << 20)}) {
      MeshArray<Adjacency> a;
      grow_array(a, 100000, Adjacency{FaceRef(1, 2), FaceRef(), FaceRef(), FaceRef()}, 0, run);
      grow_array(a, 1000000, Adjacency{}, 1000000, run);  // from a small block to a large one
      REQUIRE(a.size() == 1000000);
      CHECK(reinterpret_cast<std::uintptr_t>(a.data()) % (std::size_t{2} << 20) == 0);
      std::size_t right = 0;
      for (std::size_t i = 0; i < a.size(); ++i)
        right += a[i][0] == (i < 100000 ? FaceRef(1, 2) : FaceRef::none()) && a[i][3] == FaceRef::none();
      CHECK(right == a.size());
      MeshArray<Adjacency> b;
      b = a;  // a copy allocates its own large block
      CHECK(b == a);
      a.clear();
      a.shrink_to_fit();  // back to no block: freed through free_large
      CHECK(a.capacity() == 0);
    }
    void* p = allocate_large(kLargeBlock + 1);
    CHECK(reinterpret_cast<std::uintptr_t>(p) % (std::size_t{2} << 20) == 0);
    static_cast<char*>(p)[kLargeBlock] = 1;  // the whole block is ours
    free_large(p, kLargeBlock + 1);
  }

  TEST_CASE("edge buckets on 1, 2, 3 and 8 threads give one thread's buckets, distinct, in order") {
    // Random tets (with repeated edges) over 2000 vertices; the reference
    // is a stable sort of the tets' edges by lower vertex keeping the first
    // entry of each edge: the order one thread going through them makes.
    std::mt19937_64 r(6);
    const std::size_t capacity = 2000, n = 20000;
    std::vector<TetVertices> tets(n);
    for (auto& t : tets) {
      do {
        for (auto& v : t) v = static_cast<VertexId>(r() % capacity);
      } while (t[0] == t[1] || t[0] == t[2] || t[0] == t[3] || t[1] == t[2] || t[1] == t[3] || t[2] == t[3]);
    }
    auto tet_of = [&](std::size_t i) { return i % 5 == 3 ? kNoId : static_cast<TetId>(i); };  // some skipped
    auto vertices_of = [&](TetId t) -> const TetVertices& { return tets[t]; };
    struct Edge {
      VertexId a, b;
      TetId tet;
      bool operator==(const Edge&) const = default;
    };
    std::vector<Edge> all;
    for (std::size_t i = 0; i < n; ++i)
      if (tet_of(i) != kNoId)
        for (const auto& e : kEdgeVertex) {
          const VertexId a = tets[i][e[0]], b = tets[i][e[1]];
          all.push_back({std::min(a, b), std::max(a, b), static_cast<TetId>(i)});
        }
    std::stable_sort(all.begin(), all.end(), [](const Edge& x, const Edge& y) { return x.a < y.a; });
    std::vector<Edge> first_seen;
    std::set<std::pair<VertexId, VertexId>> seen;
    for (const Edge& e : all)
      if (seen.insert({e.a, e.b}).second) first_seen.push_back(e);
    auto by_key = first_seen;
    std::stable_sort(by_key.begin(), by_key.end(),
                     [](const Edge& x, const Edge& y) { return x.a < y.a || (x.a == y.a && x.b < y.b); });
    auto check = [&](auto policy, std::size_t parts, bool sorted) {
      using P = decltype(policy);
      std::vector<std::vector<Edge>> got(parts);
      for_each_edge_bucket<P, UpperTet>(parts, n, tet_of, vertices_of, capacity, sorted,
                                        [&](std::size_t p, VertexId a, std::span<const UpperTet> kept) {
                                          REQUIRE(p < parts);
                                          for (const UpperTet& x : kept) got[p].push_back({a, x.upper, x.tet});
                                        });
      std::vector<Edge> joined;
      for (const auto& part : got) joined.insert(joined.end(), part.begin(), part.end());
      CHECK(joined == (sorted ? by_key : first_seen));
      // Range by range of lower ends (the whole mesh's lists are made so),
      // each range counting its own lower ends or all counted at once: the
      // ranges' buckets one after the other are the same list.
      for (const bool counted_once : {false, true}) {
        CAPTURE(counted_once);
        MeshArray<std::uint32_t> counts;
        if (counted_once)
          count_keys(
              n, capacity, parts,
              [&](std::size_t i, auto&& add) {
                if (const TetId t = tet_of(i); t != kNoId) add_lower_ends(vertices_of(t), add);
              },
              [](std::size_t k, auto&& f) { P::parallel_for(k, f); }, counts);
        std::vector<Edge> ranged;
        for (LowerRange range : {LowerRange{0, 700, capacity}, LowerRange{700, 701, capacity},
                                 LowerRange{701, 1500, capacity}, LowerRange{1500, capacity, capacity}}) {
          if (counted_once) range.counts = &counts;
          std::vector<std::vector<Edge>> in_range(parts);
          for_each_edge_bucket<P, UpperTet>(parts, n, tet_of, vertices_of, range, sorted,
                                            [&](std::size_t p, VertexId a, std::span<const UpperTet> kept) {
                                              REQUIRE(a >= range.lo);
                                              REQUIRE(a < range.hi);
                                              for (const UpperTet& x : kept) in_range[p].push_back({a, x.upper, x.tet});
                                            });
          for (const auto& part : in_range) ranged.insert(ranged.end(), part.begin(), part.end());
        }
        CHECK(ranged == joined);
      }
    };
    for (bool sorted : {false, true})
      for (std::size_t parts : {1u, 2u, 3u, 8u}) {
        check(Serial{}, parts, sorted);
        check(SpeculativeOn<2>{}, parts, sorted);
        check(SpeculativeOn<8>{}, parts, sorted);
      }
    // The policies' own part count: unique_edge_seeds on 2 and 8 threads
    // gives Serial's list.
    std::vector<TetId> seeds;
    for (std::size_t i = 0; i < n; ++i) seeds.push_back(static_cast<TetId>(i));
    std::vector<EdgeSeed> serial, two, eight;
    unique_edge_seeds<Serial>(std::span<const TetId>(seeds), vertices_of, capacity, serial);
    unique_edge_seeds<SpeculativeOn<2>>(std::span<const TetId>(seeds), vertices_of, capacity, two);
    unique_edge_seeds<SpeculativeOn<8>>(std::span<const TetId>(seeds), vertices_of, capacity, eight);
    REQUIRE(serial.size() == two.size());
    REQUIRE(serial.size() == eight.size());
    for (std::size_t i = 0; i < serial.size(); ++i) {
      CHECK(serial[i].key() == two[i].key());
      CHECK(serial[i].tet == two[i].tet);
      CHECK(serial[i].key() == eight[i].key());
      CHECK(serial[i].tet == eight[i].tet);
    }
  }

  TEST_CASE("a mesh's edges and changed vertices on 2 and 8 threads are the serial ones") {
    // Above the size where the edge passes share out their work.
    Mesh mesh = make_box({.nx = 16, .ny = 16, .nz = 16});
    REQUIRE(mesh.tet_capacity() >= 16384);
    auto edges_with = [&](auto policy) {
      return collect_mesh_edges<decltype(policy), EdgeVertices>(
          mesh, [](VertexId x, VertexId y, std::vector<EdgeVertices>& part) {
            part.push_back({x, y});
          });
    };
    // Serial's list: the mesh's edges, each once, by lower vertex (the
    // order within a vertex is checked by the bucket test above).
    const auto expected = edges_with(Serial{});
    auto sorted = expected;
    std::sort(sorted.begin(), sorted.end());
    CHECK(sorted == unique_edges(mesh));
    for (std::size_t i = 1; i < expected.size(); ++i) REQUIRE(expected[i - 1][0] <= expected[i][0]);
    CHECK(edges_with(SpeculativeOn<2>{}) == expected);
    CHECK(edges_with(SpeculativeOn<8>{}) == expected);
    const Mesh::Epoch since = mesh.next_epoch();
    for (TetId t = 0; t < mesh.tet_capacity(); t += 7)
      if (mesh.tet_alive(t)) mesh.touch_tet(t);
    const auto marks = changed_vertices<Serial>(mesh, since);
    CHECK(std::count(marks.begin(), marks.end(), 1) > 0);
    CHECK(changed_vertices<SpeculativeOn<2>>(mesh, since) == marks);
    CHECK(changed_vertices<SpeculativeOn<8>>(mesh, since) == marks);
  }

  TEST_CASE("compact on 2 and 8 threads and on 3 reversed parts renumbers as on one thread: the same mesh to the bit") {
    // A coarsened box: collapses leave dead vertices and tets all through
    // the id range, the case compaction exists for.
    auto coarsened = [] {
      Mesh mesh = make_box({.nx = 16, .ny = 16, .nz = 16});
      set_uniform_metric(mesh, 0.15);
      collapse_edges<LogEuclidean, Serial>(mesh);
      return mesh;
    };
    Mesh one = coarsened();
    REQUIRE(one.tet_capacity() >= 16384);
    REQUIRE(one.tet_capacity() > one.num_tets());
    const double volume = one.volume();
    one.compact();
    require_valid(one, volume);
    // Parts run in reverse order on this thread: no part may rely on an
    // earlier one having run.
    const PartRunner reversed = reversed_parts(3);
    for (const PartRunner& run : {part_runner<SpeculativeOn<2>>(one.tet_capacity()), reversed,
                                  part_runner<SpeculativeOn<8>>(one.tet_capacity())}) {
      Mesh other = coarsened();
      other.compact(run);
      REQUIRE(other.num_tets() == one.num_tets());
      REQUIRE(other.tet_capacity() == one.tet_capacity());
      REQUIRE(other.vertex_capacity() == one.vertex_capacity());
      std::size_t same = 0;
      for (TetId t = 0; t < one.tet_capacity(); ++t) {
        bool equal = other.tet(t) == one.tet(t);
        for (int f = 0; f < 4; ++f) equal = equal && other.neighbour(t, f) == one.neighbour(t, f);
        same += equal;
      }
      CHECK(same == one.tet_capacity());
      for (VertexId v = 0; v < one.vertex_capacity(); ++v) REQUIRE(other.point(v) == one.point(v));
      require_valid(other, volume);
    }
  }

  TEST_CASE(
      "edges_beyond: every edge past the bound once, longest (shortest) first to a factor 2^(1/8), the same on 2 and 8 "
      "threads, limited to changed balls") {
    Mesh mesh = make_box({.nx = 16, .ny = 16, .nz = 16});
    // Sizes graded along x and random anisotropy, so lengths spread over
    // several classes.
    assign_graded_metric(mesh, 71, 4.0, 4.0, 60.0);
    const double step = std::exp2(1.0 / kLengthClassesPerDoubling);
    // Some tets written in a later epoch: the lists limited to it.
    const Mesh::Epoch since = mesh.next_epoch();
    for (TetId t = 0; t < mesh.tet_capacity(); t += 97) mesh.touch_tet(t);
    const std::vector<std::uint8_t> changed = changed_vertices(mesh, since);
    for (const EdgeOrder order : {EdgeOrder::longest_first, EdgeOrder::shortest_first}) {
      const bool longer = order == EdgeOrder::longest_first;
      const double bound = 1.0;
      const auto list = edges_beyond<LogEuclidean, Serial>(mesh, bound, order);
      std::vector<EdgeVertices> expected;
      for (const auto& e : unique_edges(mesh)) {
        const double l = LogEuclidean::edge_length(mesh, e[0], e[1]);
        if (longer ? l > bound : l < bound) expected.push_back(e);
      }
      std::vector<EdgeVertices> got;
      for (const auto& c : list) got.push_back({c.a, c.b});
      std::sort(got.begin(), got.end());
      REQUIRE(got == expected);
      REQUIRE(list.size() > 1000);
      // Every later item is at most 2^(1/8) longer (shorter) than any
      // earlier one; within a class the vertex ids ascend.
      double extreme = 0.0;  // the shortest (longest) length so far
      std::set<std::int32_t> classes;
      for (std::size_t i = 0; i < list.size(); ++i) {
        const double l = LogEuclidean::edge_length(mesh, list[i].a, list[i].b);
        CHECK(list[i].length_class == length_class(l));
        classes.insert(list[i].length_class);
        if (longer) {
          if (i > 0) REQUIRE(l < extreme * step);
          extreme = i == 0 ? l : std::min(extreme, l);
        } else {
          if (i > 0) REQUIRE(l > extreme / step);
          extreme = i == 0 ? l : std::max(extreme, l);
        }
        if (i > 0 && list[i].length_class == list[i - 1].length_class)
          REQUIRE((list[i - 1].a < list[i].a || (list[i - 1].a == list[i].a && list[i - 1].b < list[i].b)));
      }
      CHECK(classes.size() >= 4);
      CHECK(edges_beyond<LogEuclidean, SpeculativeOn<2>>(mesh, bound, order) == list);
      CHECK(edges_beyond<LogEuclidean, SpeculativeOn<8>>(mesh, bound, order) == list);
      // With changed_since: the same list, less the edges with no end in a
      // changed ball, in the same order.
      auto limited = list;
      std::erase_if(limited, [&](const EdgeCandidate& c) { return !changed[c.a] && !changed[c.b]; });
      REQUIRE(limited.size() > 10);
      REQUIRE(limited.size() < list.size());
      CHECK(edges_beyond<LogEuclidean, Serial>(mesh, bound, order, since) == limited);
      CHECK(edges_beyond<LogEuclidean, SpeculativeOn<2>>(mesh, bound, order, since) == limited);
    }
  }

  TEST_CASE(
      "edges_beyond from the edges outside the band at an earlier epoch: the full scan's list, on 1 and 2 threads") {
    Mesh mesh = make_box({.nx = 12, .ny = 12, .nz = 12});
    // Short edges at small x, long ones at large x.
    assign_graded_metric(mesh, 72, 3.0, 20.0, 400.0);
    mesh.compact();
    OutOfBandEdges known;
    conformity<LogEuclidean, Serial>(mesh, nullptr, false, &known.edges);
    known.taken(mesh);
    REQUIRE(known.edges.size() > 1000);
    // Bounds outside the band, on both sides, and one inside it.
    struct Bound {
      double length;
      EdgeOrder order;
    };
    const std::vector<Bound> bounds{{kUnitBand.lo, EdgeOrder::shortest_first},
                                    {0.5, EdgeOrder::shortest_first},
                                    {kUnitBand.hi, EdgeOrder::longest_first},
                                    {2.0, EdgeOrder::longest_first}};
    auto same_as_scan = [&](const Bound& b, Mesh::Epoch since, bool from_known) {
      const auto scan = edges_beyond<LogEuclidean, Serial>(mesh, b.length, b.order, since);
      CHECK(edges_beyond<LogEuclidean, Serial>(mesh, b.length, b.order, since, &known) == scan);
      CHECK(edges_beyond<LogEuclidean, SpeculativeOn<2>>(mesh, b.length, b.order, since, &known) == scan);
      // Whether the list came from `known` (the same list either way).
      std::vector<EdgeCandidate> unused;
      const bool longer = b.order == EdgeOrder::longest_first;
      auto all = [&](VertexId, VertexId, std::vector<EdgeCandidate>&) {};
      CHECK(detail::edges_from_known<Serial>(mesh, b.length, longer, &known, all, unused) == from_known);
      return scan.size();
    };
    for (const Bound& b : bounds) CHECK(same_as_scan(b, 0, true) > 10);
    // A few collapses, splits and moves around a corner of the box: the
    // vertices changed since are few, the edges at them are measured anew.
    const Mesh::Epoch local = mesh.next_epoch();
    for (TetId t = 0; t < mesh.tet_capacity(); ++t)
      if (mesh.tet_alive(t) && mesh.tet_point(t, 0).y() > 0.85 && mesh.tet_point(t, 0).z() > 0.85) mesh.touch_tet(t);
    const Mesh::Epoch changes = mesh.next_epoch();
    const OperatorStats collapsed = collapse_edges<LogEuclidean, Serial>(
        mesh, {.max_new_length = 3.0, .shape_floor = 0.0, .scope = {.changed_since = local}});
    INFO("collapses tried " << collapsed.tried);
    CHECK(collapsed.applied > 0);
    CHECK(refine_edges<LogEuclidean, Serial>(mesh, {.scope = {.changed_since = local}}).applied > 0);
    TetList ball;
    std::size_t moved = 0;
    for (VertexId v = 0; v < mesh.vertex_capacity() && moved < 20; ++v) {
      if (!mesh.vertex_alive(v) || mesh.vertex_class(v) != VertexClass::interior || mesh.point(v).x() > 0.5) continue;
      // A small move that keeps the ball positive.
      vertex_ball(mesh, v, ball);
      const Point p = mesh.point(v) + Point(1e-3, -1e-3, 5e-4);
      if (!ball_positive_at(mesh, v, ball, p)) continue;
      mesh.point(v) = p;
      for (TetId t : ball) mesh.touch_tet(t);
      ++moved;
    }
    REQUIRE(moved == 20);
    require_valid(mesh, 1.0);
    {
      const auto changed = changed_vertices(mesh, known.epoch);
      const auto n = static_cast<std::size_t>(std::count(changed.begin(), changed.end(), 1));
      INFO(n << " of " << mesh.num_vertices() << " vertices changed");
      REQUIRE(4 * n < mesh.num_vertices());
    }
    for (const Bound& b : bounds) {
      same_as_scan(b, 0, true);
      same_as_scan(b, changes, true);
    }
    // Not from `known`: a bound inside the band, or after a compaction.
    same_as_scan({1.0, EdgeOrder::shortest_first}, 0, false);
    same_as_scan({1.2, EdgeOrder::longest_first}, 0, false);
    mesh.compact();
    same_as_scan(bounds[0], 0, false);
    // Nor when most vertices changed.
    conformity<LogEuclidean, Serial>(mesh, nullptr, false, &known.edges);
    known.taken(mesh);
    for (TetId t = 0; t < mesh.tet_capacity(); t += 2) mesh.touch_tet(t);
    same_as_scan(bounds[2], 0, false);
  }

  TEST_CASE("following the load: the cores other processes leave, at least one thread, at most those wanted") {
    // 2 cores: idle (the caller alone, or with its own threads running),
    // one busy neighbour, two.
    CHECK(threads_for_load(2, 2, 1, 1) == 2);
    CHECK(threads_for_load(2, 2, 3, 3) == 2);
    CHECK(threads_for_load(2, 2, 2, 1) == 1);
    CHECK(threads_for_load(2, 2, 3, 1) == 1);
    CHECK(threads_for_load(8, 16, 5, 1) == 8);
    CHECK(threads_for_load(8, 16, 13, 1) == 4);
    CHECK(threads_for_load(1, 64, 1, 0) == 1);
    // This process runs (the caller reads), so the machine has a task
    // ready to run and so does the process; when the process may not use
    // every core of the machine, the machine's count is not given.
    if (sysconf(_SC_NPROCESSORS_ONLN) == core_count())
      CHECK(runnable_tasks() >= 1);
    else
      CHECK(runnable_tasks() == 0);
    CHECK(own_runnable_threads() >= 1);
    // follow_load sets a count between one and the threads wanted; off,
    // the threads wanted.
    ThreadCountGuard guard;
    set_thread_count(3);
    SpeculativeScope scope{{.follow_load = true}};
    Speculative::follow_load();
    // (0: the load is not known, the threads wanted stand.)
    CHECK(Speculative::settings().load_threads == (runnable_tasks() > 0 ? Speculative::threads() : 0));
    CHECK(Speculative::threads() >= 1);
    CHECK(Speculative::threads() <= 3);
    Speculative::settings().follow_load = false;
    CHECK(Speculative::threads() == 3);
  }

  TEST_CASE("Speculative on 1 thread: no conflict, a valid mesh of the serial quality") {
    ThreadCountGuard guard;
    const Adapted serial = adapt_linear_serial();
    set_thread_count(1);
    const Adapted one = adapt_linear("speculative");
    require_valid(one.mesh, 1.0);
    CHECK(total_conflicts(one.report) == 0);
    const auto& s = serial.report.cycles.back();
    const auto& p = one.report.cycles.back();
    INFO("serial " << s.conformity << " / " << s.min_quality << ", speculative " << p.conformity << " / "
                   << p.min_quality);
    CHECK(std::abs(p.conformity - s.conformity) <= 0.02);
    CHECK(p.min_quality >= 0.3);
  }

  TEST_CASE("Speculative on 2 and 8 threads: valid meshes of the serial quality") {
    ThreadCountGuard guard;
    const Adapted serial = adapt_linear_serial();
    for (int threads : {2, 8}) {
      CAPTURE(threads);
      set_thread_count(threads);
      const Adapted a = adapt_linear_shared();
      require_valid(a.mesh, 1.0);
      const auto& s = serial.report.cycles.back();
      const auto& p = a.report.cycles.back();
      INFO("serial " << s.conformity << " / " << s.min_quality << ", speculative " << p.conformity << " / "
                     << p.min_quality << ", conflicts " << total_conflicts(a.report));
      CHECK(std::abs(p.conformity - s.conformity) <= 0.03);
      CHECK_MESSAGE(p.min_quality >= 0.3, worst_tets(a));
      CHECK(std::abs(double(p.vertices) - double(s.vertices)) <= 0.1 * double(s.vertices));
    }
  }

  TEST_CASE("a list shorter than the small-list size runs on one thread and splits what Serial splits") {
    // Splits lock shells holding vertices made earlier in the pass, past
    // the vertex capacity the pass began with: the owner words must cover
    // them (they once did not, and such splits were dropped).
    Mesh a = make_box({.nx = 2, .ny = 2, .nz = 2});
    set_uniform_metric(a, 0.12);
    Mesh b = a;
    const auto s = refine_edges<LogEuclidean, Serial>(a);
    const SpeculativeScope small({.threads = 2, .small_list = 1000000});
    const auto p = refine_edges<LogEuclidean, Speculative>(b);
    CHECK(s.applied > 20);
    CHECK(p.applied == s.applied);
    CHECK(p.conflicts == 0);
    CHECK(sorted_tets(a) == sorted_tets(b));
    require_valid(b, 1.0);
  }

  TEST_CASE("Serial adaptation gives the same mesh to the bit on every run") {
    const Adapted a = adapt_linear("serial");
    const Adapted b = adapt_linear("serial");
    const auto da = extract_mesh_data(a.mesh), db = extract_mesh_data(b.mesh);
    REQUIRE(da.vertices.size() == db.vertices.size());
    REQUIRE(da.tets.size() == db.tets.size());
    CHECK(da.vertices == db.vertices);
    CHECK(da.tets == db.tets);
  }

  TEST_CASE(
      "operator counts add up on every executor: tried = applied + rejected + deferred - none deferred on one thread") {
    auto check = [](const AdaptReport& r, bool serial) {
      REQUIRE(!r.ops.empty());
      for (const auto& [stage, s] : r.ops) {
        const std::string& name = stage;  // clang cannot capture a structured binding
        CAPTURE(name);
        CHECK(s.tried == s.applied + s.rejected + s.deferred);
        CHECK(s.candidates >= s.tried);
        if (serial) CHECK(s.deferred == 0);
        if (serial) CHECK(s.conflicts == 0);
      }
      CHECK(r.ops.get("flip").candidates > r.ops.get("flip").tried);  // flips weigh several configurations
    };
    check(adapt_linear_serial().report, true);
    check(adapt_linear_shared().report, false);
  }
}
