#include <metrica/distributed/neighbours.hpp>
#include <metrica/distributed/pinches.hpp>

#include <numeric>

namespace metrica::distributed {

namespace {

int root_of(std::vector<int>& parent, int i) {
  while (parent[std::size_t(i)] != i) i = parent[std::size_t(i)] = parent[std::size_t(parent[std::size_t(i)])];
  return i;
}

// Groups of `items` joined when joined(a, b); how many.
template <class Joined>
int groups(int items, Joined&& joined) {
  std::vector<int> parent(static_cast<std::size_t>(items));
  std::iota(parent.begin(), parent.end(), 0);
  for (int a = 0; a < items; ++a)
    for (int b = a + 1; b < items; ++b)
      if (joined(a, b)) parent[std::size_t(root_of(parent, a))] = root_of(parent, b);
  int count = 0;
  for (int a = 0; a < items; ++a) count += root_of(parent, a) == a;
  return count;
}

int common(const auto& a, const auto& b) {
  int s = 0;
  for (auto x : a)
    for (auto y : b) s += x == y;
  return s;
}

}  // namespace

std::vector<bool> adaptable_tets(const Part& part, std::vector<bool> wanted) {
  const VertexIndex index(part.vertex_ids);
  const std::size_t nv = part.vertex_ids.size(), nt = part.tets.size();
  std::vector<bool> active = wanted.empty() ? std::vector<bool>(nt, true) : std::move(wanted);
  const TetsAround tets_around(part);
  const auto& first = tets_around.first;
  const auto& around = tets_around.around;
  // The vertices to look at: those of faces not between two active tets
  // other than the outer boundary (the input's boundary is a manifold).
  std::vector<std::uint32_t> watch;
  for (const auto& f : part.shared_faces)
    for (GlobalId g : f) watch.push_back(std::uint32_t(index.find(g)));
  // and those between the tets wanted and the others.
  {
    std::vector<bool> in_active(nv, false);
    for (std::size_t t = 0; t < nt; ++t)
      if (active[t])
        for (auto v : part.tets[t]) in_active[v] = true;
    for (std::size_t t = 0; t < nt; ++t)
      if (!active[t])
        for (auto v : part.tets[t])
          if (in_active[v]) watch.push_back(v);
  }
  std::vector<std::uint32_t> shell;
  // Faces by their sorted local vertices (nothing leaves this function).
  using Key = std::array<std::uint32_t, 3>;
  const auto key_of = [](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    Key k{a, b, c};
    std::sort(k.begin(), k.end());
    return k;
  };
  std::vector<Key> faces, boundary;
  for (int sweep = 0; !watch.empty(); ++sweep) {
    std::sort(watch.begin(), watch.end());
    watch.erase(std::unique(watch.begin(), watch.end()), watch.end());
    std::vector<std::uint32_t> dropped;
    for (auto v : watch) {
      shell.clear();
      for (auto i = first[v]; i < first[v + 1]; ++i)
        if (active[around[i]]) shell.push_back(around[i]);
      if (shell.empty()) continue;
      const int k = int(shell.size());
      // The active tets around v in one piece (joined by faces)...
      bool pinched = groups(k, [&](int a, int b) {
                       return common(part.tets[shell[std::size_t(a)]], part.tets[shell[std::size_t(b)]]) == 3;
                     }) > 1;
      // ... whose boundary at v is one umbrella ...
      if (!pinched) {
        faces.clear();
        for (auto t : shell) {
          const auto& tv = part.tets[t];
          for (const auto& f : kTetFaces) {
            const auto key = key_of(tv[std::size_t(f[0])], tv[std::size_t(f[1])], tv[std::size_t(f[2])]);
            if (std::find(key.begin(), key.end(), v) != key.end()) faces.push_back(key);
          }
        }
        std::sort(faces.begin(), faces.end());
        boundary.clear();
        for (std::size_t i = 0; i < faces.size();) {
          std::size_t j = i;
          while (j < faces.size() && faces[j] == faces[i]) ++j;
          if (j - i == 1) boundary.push_back(faces[i]);
          i = j;
        }
        pinched = groups(int(boundary.size()), [&](int a, int b) {
                    return common(boundary[std::size_t(a)], boundary[std::size_t(b)]) == 2;
                  }) > 1;
      }
      // ... and each edge from v in one piece too.
      if (!pinched) {
        for (const auto& f : boundary) {
          for (std::uint32_t w : f) {
            if (w == v || pinched) continue;
            std::vector<std::uint32_t> edge;
            for (auto t : shell)
              if (std::find(part.tets[t].begin(), part.tets[t].end(), w) != part.tets[t].end()) edge.push_back(t);
            pinched = groups(int(edge.size()), [&](int a, int b) {
                        return common(part.tets[edge[std::size_t(a)]], part.tets[edge[std::size_t(b)]]) == 3;
                      }) > 1;
          }
          if (pinched) break;
        }
      }
      if (!pinched) continue;
      for (auto t : shell) {
        active[t] = false;
        for (auto u : part.tets[t]) dropped.push_back(u);
      }
    }
    // The vertices of the tets kept out now border them: look again.
    watch.swap(dropped);
  }
  return active;
}

std::vector<bool> tets_near(const Part& part, const std::vector<GlobalId>& near, int layers) {
  const std::size_t nv = part.vertex_ids.size(), nt = part.tets.size();
  const TetsAround tets_around(part);
  const auto& first = tets_around.first;
  const auto& around = tets_around.around;
  std::vector<int> depth(nv, -1);
  std::vector<std::uint32_t> front, grown;
  for (std::size_t v = 0; v < nv; ++v)
    if (std::binary_search(near.begin(), near.end(), part.vertex_ids[v]))
      depth[v] = 0, front.push_back(std::uint32_t(v));
  for (int layer = 1; layer < layers && !front.empty(); ++layer) {
    grown.clear();
    for (auto v : front)
      for (auto i = first[v]; i < first[v + 1]; ++i)
        for (auto u : part.tets[around[i]]) {
          if (depth[u] < 0) depth[u] = layer, grown.push_back(std::uint32_t(u));
        }
    front.swap(grown);
  }
  std::vector<bool> in(nt, false);
  for (std::size_t t = 0; t < nt; ++t)
    for (auto v : part.tets[t]) in[t] = in[t] || depth[v] >= 0;
  return in;
}

}  // namespace metrica::distributed
