// Read/write speed of libMeshb files and of adjacency construction on a
// generated box mesh. Prints the median of several runs, in MB/s and
// million tets per second.
//
//   build/bench/bench_io [hexes-per-direction=55] [runs=5] [folder=/tmp]
//
// 55^3 hexes x 6 = 998,250 tets (the 1M-tet cube).
#include "bench_common.hpp"

#include <metrica/box.hpp>
#include <metrica/io/meshb.hpp>
#include <metrica/mesh_build.hpp>
#include <metrica/policies/threads.hpp>
#include <metrica/timer.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

using metrica::bench::median_seconds;

int main(int argc, char** argv) {
  using namespace metrica;
  const int n = argc > 1 ? std::stoi(argv[1]) : 55;
  const int runs = argc > 2 ? std::stoi(argv[2]) : 5;
  const std::string dir = argc > 3 ? argv[3] : "/tmp";

  const auto data = box_mesh_data({.nx = n, .ny = n, .nz = n});
  fmt::print("box {}^3 hexes: {} vertices, {} tets, {} triangles; {} runs each, median; {} cores\n", n,
             data.vertices.size(), data.tets.size(), data.triangles.size(), runs, core_count());
  fmt::print("{:<28} {:>10} {:>10} {:>12} {:>12}\n", "step", "MB", "seconds", "MB/s", "Mtets/s");
  auto row = [&](const char* what, double bytes, double s) {
    fmt::print("{:<28} {:>10.1f} {:>10.3f} {:>12.1f} {:>12.2f}\n", what, bytes / 1e6, s, bytes / 1e6 / s,
               double(data.tets.size()) / 1e6 / s);
  };
  for (const char* ext : {".meshb", ".mesh"}) {
    const std::string path = dir + "/metrica-bench" + ext;
    const double w = median_seconds(runs, [&] { io::write_meshb(path, data); });
    const double bytes = double(std::filesystem::file_size(path));
    io::MeshData back;
    const double r = median_seconds(runs, [&] { back = io::read_meshb(path); });
    if (!(back == data)) {
      fmt::print(stderr, "round trip through {} changed the mesh\n", path);
      return 1;
    }
    row(fmt::format("write {}", ext).c_str(), bytes, w);
    row(fmt::format("read {}", ext).c_str(), bytes, r);
    std::filesystem::remove(path);
  }
  const double b = median_seconds(runs, [&] { (void)build_mesh(data); });
  fmt::print("{:<28} {:>10} {:>10.3f} {:>12} {:>12.2f}\n", "build adjacency + classify", "", b, "",
             double(data.tets.size()) / 1e6 / b);
  return 0;
}
