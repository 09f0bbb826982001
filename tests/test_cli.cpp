// The `metrica` command end to end: counts on the UGAWG files, exit codes
// (0 ok, 1 invalid input, 2 usage; never a signal), atomic outputs.
#include "cli_test_support.hpp"
#include "test_support.hpp"

#include <metrica/io/meshb.hpp>
#include <metrica/metrics/metric_field.hpp>
#include <metrica/metrics/sym_tensor.hpp>

#include <doctest/doctest.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sys/wait.h>

using namespace metrica;
using test::has;
using test::metrica_cli;
using test::metrica_cli_in_env;
using test::Run;
using test::serial_option;

namespace {

// The position of the n-th comma (1-based) of a CSV line.
std::size_t nth_comma(const std::string& line, int n) {
  std::size_t at = std::string::npos;
  for (int i = 0; i < n; ++i) at = line.find(',', at == std::string::npos ? 0 : at + 1);
  return at;
}

}  // namespace

TEST_SUITE("regression") {
  TEST_CASE("OpenMP's threads wait passively unless the environment chooses - the command runs once") {
    auto run = [](const std::string& env) { return metrica_cli_in_env(env + " OMP_DISPLAY_ENV=verbose", "--version"); };
    const Run by_default = run("env -u OMP_WAIT_POLICY");
    CHECK(by_default.code == 0);
    std::size_t versions = 0;
    for (std::size_t at = by_default.output.find("metrica "); at != std::string::npos;
         at = by_default.output.find("metrica ", at + 1))
      ++versions;
    CHECK(versions == 1);
    // libgomp prints its spin count: 0 once passive (its display of the
    // policy says PASSIVE also while it spins).
    if (has(by_default, "GOMP_SPINCOUNT")) {
      CHECK(has(by_default, "GOMP_SPINCOUNT = '0'"));
      CHECK(has(run("env OMP_WAIT_POLICY=active"), "OMP_WAIT_POLICY = 'ACTIVE'"));
    }
  }

  TEST_CASE("info prints the counts of every UGAWG file - check says valid") {
    struct Case {
      const char* file;
      const char* vertices;
      const char* triangles;
      const char* tets;
    };
    for (const auto& c :
         {Case{"cube-linear-00.mesh", "64", "108", "162"}, Case{"cube-linear-00.meshb", "64", "108", "162"},
          Case{"cube-cylinder.mesh", "286", "418", "952"}, Case{"cube-cylinder.meshb", "286", "418", "952"},
          Case{"cone-cone.meshb", "17", "28", "23"}}) {
      CAPTURE(c.file);
      const auto info = metrica_cli("info " + test::ugawg(c.file));
      CHECK(info.code == 0);
      CHECK(has(info, std::string("vertices             ") + c.vertices + "\n"));
      CHECK(has(info, std::string("triangles            ") + c.triangles + "\n"));
      CHECK(has(info, std::string("tetrahedra           ") + c.tets + "\n"));
      const auto check = metrica_cli("check " + test::ugawg(c.file));
      CHECK(check.code == 0);
      CHECK(has(check, "valid"));
    }
    const auto cube = metrica_cli("info -i " + test::ugawg("cube-linear-00.meshb"));
    CHECK(has(cube, "12 curves, 36 edges"));
    CHECK(has(cube, "corners              8"));
  }

  TEST_CASE("cube then convert and check chain through every format") {
    test::TempDir dir;
    CHECK(metrica_cli("cube --n 3 -o " + (dir / "c.meshb")).code == 0);
    CHECK(metrica_cli("convert " + (dir / "c.meshb") + " " + (dir / "c.mesh") + " --format-version 4").code == 0);
    CHECK(metrica_cli("convert -i " + (dir / "c.mesh") + " -o " + (dir / "c3.meshb") + " --format-version 3").code ==
          0);
    CHECK(metrica_cli("convert " + (dir / "c3.meshb") + " " + (dir / "c.vtu")).code == 0);
    CHECK(metrica_cli("convert " + (dir / "c3.meshb") + " " + (dir / "c.su2")).code == 0);
    CHECK(metrica_cli("check " + (dir / "c3.meshb")).code == 0);
    // .vtu and .su2 read back: the same points and tets.
    for (const char* back : {"c.vtu", "c.su2"}) {
      CHECK(metrica_cli("convert " + (dir / back) + " " + (dir / "back.meshb")).code == 0);
      const auto x = io::read_meshb(dir / "c3.meshb"), y = io::read_meshb(dir / "back.meshb");
      CHECK(x.vertices == y.vertices);
      CHECK(x.tets == y.tets);
    }
    auto a = io::read_meshb(dir / "c.meshb"), b = io::read_meshb(dir / "c3.meshb");
    CHECK(b.version == 3);
    b.version = a.version;
    CHECK(a == b);
    CHECK(metrica_cli("cube --n 2 3 4 --lo=-1,-1,-1 --hi 1,1,1 -o " + (dir / "b.mesh")).code == 0);
    CHECK(has(metrica_cli("info " + (dir / "b.mesh")), "volume               8\n"));
    CHECK(metrica_cli("convert " + test::ugawg("cube-linear-00.solb") + " " + (dir / "m.sol")).code == 0);
    CHECK(io::read_sol(dir / "m.sol") == io::read_sol(test::ugawg("cube-linear-00.solb")));
  }

  TEST_CASE("metric --analytic linear reproduces the UGAWG solution") {
    test::TempDir dir;
    const auto r =
        metrica_cli("metric " + test::ugawg("cube-linear-00.meshb") + " --analytic linear -o " + (dir / "m.solb"));
    CHECK(r.code == 0);
    const auto ours = io::read_sol(dir / "m.solb"), ref = io::read_sol(test::ugawg("cube-linear-00.solb"));
    REQUIRE(ours.values.size() == ref.values.size());
    for (std::size_t i = 0; i < ours.values.size(); ++i)
      CHECK(ours.values[i] == doctest::Approx(ref.values[i]).epsilon(1e-12));
    CHECK(metrica_cli("metric " + test::ugawg("cube-linear-00.meshb") + " --analytic cubic -o " + (dir / "x.solb"))
              .code == 2);
    CHECK_FALSE(std::filesystem::exists(dir / "x.solb"));
  }

  TEST_CASE("metric from a field then quality: complexity on target and a CSV report") {
    test::TempDir dir;
    REQUIRE(metrica_cli("cube --n 8 -o " + (dir / "c.meshb")).code == 0);
    const auto m = metrica_cli("metric " + (dir / "c.meshb") +
                               " --field tanh3 --complexity 3000 --gradation 3 --hmax 0.5 -o " + (dir / "m.solb"));
    CHECK(m.code == 0);
    CHECK(has(m, "complexity 30"));  // 3000 within 0.5 percent: 29xx or 30xx
    const auto q =
        metrica_cli("quality " + (dir / "c.meshb") + " -m " + (dir / "m.solb") + " --csv " + (dir / "q.csv"));
    CHECK(q.code == 0);
    CHECK(has(q, "edges in [1/sqrt2, sqrt2]"));
    CHECK(has(q, "mean ratio histogram"));
    std::ifstream csv(dir / "q.csv");
    std::string line;
    std::getline(csv, line);
    CHECK(line == "section,key,lo,hi,value");
    std::getline(csv, line);
    CHECK(line == "summary,vertices,,,729");
    // A scalar field from a file, intersected with an analytic metric.
    io::SolData f;
    f.count = 729;
    f.types = {io::SolType::scalar};
    const auto mesh = io::read_meshb(dir / "c.meshb");
    for (const auto& p : mesh.vertices) f.values.push_back(p.x() * p.x() + 3 * p.y() * p.z());
    io::write_sol(dir / "f.solb", f);
    REQUIRE(metrica_cli("metric " + (dir / "c.meshb") + " --analytic linear -o " + (dir / "lin.solb")).code == 0);
    const auto mf = metrica_cli("metric " + (dir / "c.meshb") + " --field-file " + (dir / "f.solb") +
                                " --complexity 500 --intersect " + (dir / "lin.solb") + " -o " + (dir / "mf.solb"));
    CHECK(mf.code == 0);
    CHECK(has(mf, "intersected with"));
    // Options out of their domain: exit 2, nothing written.
    CHECK(metrica_cli("metric " + (dir / "c.meshb") + " --field tanh3 --complexity 0 -o " + (dir / "z.solb")).code ==
          2);
    CHECK(metrica_cli("metric " + (dir / "c.meshb") + " --field tanh3 --norm 0.5 -o " + (dir / "z.solb")).code == 2);
    CHECK(metrica_cli("metric " + (dir / "c.meshb") + " --field tanh3 --hmin 2 --hmax 1 -o " + (dir / "z.solb")).code ==
          2);
    CHECK(metrica_cli("metric " + (dir / "c.meshb") + " --field tanh3 --gradation 0.5 -o " + (dir / "z.solb")).code ==
          2);
    const auto wrong = metrica_cli("quality " + test::ugawg("cube-linear-00.meshb") + " -m " + (dir / "m.solb"));
    CHECK(wrong.code == 1);
    CHECK(has(wrong, "729 entries but the mesh has 64 vertices"));
    CHECK_FALSE(std::filesystem::exists(dir / "z.solb"));
  }

  TEST_CASE("- is standard output for every output: the bytes of the file - progress on standard error") {
    test::TempDir dir;
    const std::string cube = test::ugawg("cube-linear-00.meshb"), metric = test::ugawg("cube-linear-00.solb");
    // stdout and stderr to files of their own.
    auto run = [&](const std::string& args) {
      const std::string cmd = std::string(METRICA_CLI) + " " + args + " >" + (dir / "out") + " 2>" + (dir / "err");
      const int status = std::system(cmd.c_str());
      return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    };
    auto slurp = [&](const std::string& name) {
      std::ifstream in(dir / name, std::ios::binary);
      return std::string(std::istreambuf_iterator<char>(in), {});
    };
    for (const std::string& target : {std::string("-"), std::string("/dev/stdout")}) {
      CAPTURE(target);
      REQUIRE(run("quality " + cube + " -m " + metric + " --csv " + target) == 0);
      REQUIRE(metrica_cli("quality " + cube + " -m " + metric + " --csv " + (dir / "q.csv") + " -q").code == 0);
      CHECK(slurp("out") == slurp("q.csv"));
      CHECK(slurp("err").find("mean ratio histogram") != std::string::npos);  // the report, beside the data
    }
    // A mesh: ASCII .mesh, the same as the file; a metric: ASCII .sol.
    REQUIRE(run("convert " + cube + " -") == 0);
    REQUIRE(metrica_cli("convert " + cube + " " + (dir / "c.mesh")).code == 0);
    CHECK(slurp("out") == slurp("c.mesh"));
    REQUIRE(run("adapt " + cube + " -m " + metric + serial_option() + " --cycles 2 --quality-passes 1 -o " +
                (dir / "a.meshb") + " --metric-out -") == 0);
    CHECK(slurp("out").rfind("MeshVersionFormatted", 0) == 0);
    CHECK(slurp("out").find("SolAtVertices") != std::string::npos);
    CHECK(slurp("err").find("in range") != std::string::npos);
    // Two outputs on standard output: usage error, nothing written.
    CHECK(run("adapt " + cube + " -m " + metric + " -o - --metric-out -") == 2);
    CHECK(slurp("err").find("both standard output") != std::string::npos);
    // A failed run writes nothing to standard output.
    CHECK(run("quality " + cube + " -m " + (dir / "missing.solb") + " --csv -") == 1);
    CHECK(slurp("out").empty());
  }

  TEST_CASE("adapt writes a valid mesh and its metric - quality reads them back") {
    test::TempDir dir;
    REQUIRE(metrica_cli("cube --n 2 -o " + (dir / "c.meshb")).code == 0);
    REQUIRE(metrica_cli("metric " + (dir / "c.meshb") + " --analytic linear --complexity 300 -o " + (dir / "m.solb"))
                .code == 0);
    const auto r = metrica_cli("adapt " + (dir / "c.meshb") + " -m " + (dir / "m.solb") + " -o " + (dir / "a.meshb") +
                               " --metric-out " + (dir / "a.solb") + " --vtu " + (dir / "a.vtu"));
    INFO(r.output);
    REQUIRE(r.code == 0);
    CHECK(has(r, "cycle "));
    CHECK(has(r, "polish"));
    CHECK(has(r, "edges in [1/sqrt2, sqrt2]"));
    CHECK(metrica_cli("check " + (dir / "a.meshb")).code == 0);
    const auto q = metrica_cli("quality " + (dir / "a.meshb") + " -m " + (dir / "a.solb"));
    CHECK(q.code == 0);
    // The report is in the field given: the input metric on the input mesh,
    // as quality measures it with --metric-mesh (and --metric-out is it).
    const auto user =
        metrica_cli("quality " + (dir / "a.meshb") + " -m " + (dir / "m.solb") + " --metric-mesh " + (dir / "c.meshb"));
    REQUIRE(user.code == 0);
    auto in_range = [](const Run& x) {
      const auto at = x.output.find("edges in [1/sqrt2, sqrt2]");
      return at == std::string::npos ? std::string("none") : x.output.substr(at, x.output.find('\n', at) - at);
    };
    CHECK(in_range(user) == in_range(r));
    CHECK(in_range(user) == in_range(q));
    CHECK(metrica_cli("quality " + (dir / "a.meshb") + " --analytic linear --metric-mesh " + (dir / "c.meshb")).code ==
          2);
    CHECK(std::filesystem::exists(dir / "a.vtu"));
    // The UGAWG loop form: analytic metric, two iterations.
    const auto l = metrica_cli("adapt " + (dir / "c.meshb") + " --analytic polar-1 --iterations 2 --cycles 2 " +
                               "--quality-passes 1 -o " + (dir / "p.meshb"));
    CHECK(l.code == 0);
    CHECK(has(l, "iteration 2:"));
    // The centroid point-creation rule.
    const auto c = metrica_cli("adapt " + (dir / "c.meshb") + " --analytic linear --points centroid --cycles 3 " +
                               "--quality-passes 1 -o " + (dir / "q.meshb"));
    INFO(c.output);
    CHECK(c.code == 0);
    CHECK(has(c, "centroid points"));
    CHECK(metrica_cli("check " + (dir / "q.meshb")).code == 0);
  }

  TEST_CASE("adapt -v accounts for the time: each pass in and outside its loops, the parts adding up") {
    test::TempDir dir;
    REQUIRE(metrica_cli("cube --n 2 -o " + (dir / "c.meshb")).code == 0);
    for (const char* threads : {"1", "2"}) {
      const auto r = metrica_cli("adapt " + (dir / "c.meshb") + " --analytic linear --cycles 3 --quality-passes 1 -v " +
                                 "--threads " + threads + " -o " + (dir / "a.meshb"));
      INFO(r.output);
      REQUIRE(r.code == 0);
      // Each operator's line ends with its seconds and those outside its loops.
      double split = -1, split_outside = -1;
      const auto at = r.output.find("  split    tried");
      REQUIRE(at != std::string::npos);
      const std::string line = r.output.substr(at, r.output.find('\n', at) - at);
      REQUIRE(std::sscanf(line.c_str() + line.rfind('|'), "| %lf s, outside loops %lf s", &split, &split_outside) == 2);
      CHECK(split_outside >= 0.0);
      CHECK(split_outside <= split);
      // The summary: passes = in their loops + outside, and the parts within the whole.
      double passes = 0, in_loops = 0, outside = 0, ends = 0, rest = 0, whole = 0;
      const auto t = r.output.find("  time: passes");
      REQUIRE(t != std::string::npos);
      REQUIRE(std::sscanf(r.output.c_str() + t,
                          "  time: passes %lf s (in their loops %lf s, outside %lf s), cycle ends (compaction, "
                          "measures) %lf s, the rest %lf s, of %lf s",
                          &passes, &in_loops, &outside, &ends, &rest, &whole) == 6);
      CHECK(std::abs(in_loops + outside - passes) <= 0.011);  // each printed to 0.01 s
      CHECK(passes + ends + rest <= whole + 0.02);
      CHECK(passes > 0.0);
    }
  }

  TEST_CASE("pipeline runs the stages composed on the command line - the same mesh on every serial run") {
    test::TempDir dir;
    REQUIRE(metrica_cli("cube --n 2 -o " + (dir / "c.meshb")).code == 0);
    REQUIRE(metrica_cli("metric " + (dir / "c.meshb") + " --analytic linear --complexity 300 -o " + (dir / "m.solb"))
                .code == 0);
    const std::string stages =
        " --cycle collapse,split,delaunay=flip:criterion=metric-delaunay,smooth:below=0.3 --polish flip,smooth:below=1"
        " --cycles 4 --quality-passes 1" +
        serial_option();
    const auto r =
        metrica_cli("pipeline " + (dir / "c.meshb") + " -m " + (dir / "m.solb") + " -o " + (dir / "a.meshb") + stages);
    INFO(r.output);
    REQUIRE(r.code == 0);
    CHECK(has(r, "| delaunay "));  // the stage's name in the cycle lines
    CHECK(has(r, "polish"));
    CHECK(has(r, "edges in [1/sqrt2, sqrt2]"));
    CHECK(metrica_cli("check " + (dir / "a.meshb")).code == 0);
    REQUIRE(
        metrica_cli("pipeline " + (dir / "c.meshb") + " -m " + (dir / "m.solb") + " -o " + (dir / "b.meshb") + stages)
            .code == 0);
    CHECK(io::read_file_bytes(dir / "a.meshb") == io::read_file_bytes(dir / "b.meshb"));
    // An analytic metric, on threads.
    const auto t = metrica_cli("pipeline " + (dir / "c.meshb") + " --analytic polar-1 -o " + (dir / "t.meshb") +
                               " --cycle collapse,split,flip --cycles 3 --threads 2");
    CHECK(t.code == 0);
    CHECK(metrica_cli("check " + (dir / "t.meshb")).code == 0);
    // Usage: each refusal names what is wrong; nothing is written.
    const std::string in = "pipeline " + (dir / "c.meshb") + " --analytic linear -o " + (dir / "x.meshb");
    const auto unknown = metrica_cli(in + " --cycle collapse,refine");
    CHECK(unknown.code == 2);
    CHECK(has(unknown, "unknown operation 'refine' (collapse, split, centroids, flip, smooth, swap)"));
    const auto range = metrica_cli(in + " --cycle flip:seed_below=3");
    CHECK(range.code == 2);
    CHECK(has(range, "seed_below must be a number in [0, 1]"));
    CHECK(has(metrica_cli(in + " --cycle smooth:below"), "is not OPTION=VALUE"));
    CHECK(has(metrica_cli(in + " --cycle split,split"), "two stages named 'split'"));
    CHECK(metrica_cli(in).code == 2);  // no stage
    CHECK(metrica_cli(in + " --cycle split --cycles 2.5").code == 2);
    CHECK(metrica_cli(in + " --cycle split --concurrency gpu").code == 2);
    CHECK(!std::filesystem::exists(dir / "x.meshb"));
  }

  TEST_CASE("loop writes one CSV row per iteration and each mesh - interpolate transfers a field") {
    test::TempDir dir;
    const auto r = metrica_cli("loop --field tanh3 --iterations 2 --complexity 500 --csv " + (dir / "l.csv") +
                               " --output-dir " + (dir / "run") + " --interpolate --threads 2 --format-version 3");
    INFO(r.output);
    REQUIRE(r.code == 0);
    CHECK(has(r, "L2 error"));
    CHECK(has(r, "transfer"));
    std::ifstream in(dir / "l.csv");
    std::string header, line;
    std::getline(in, header);
    CHECK(header == "iteration,complexity,vertices,tets,seconds,l2_error,transfer_error,conformity,min_q");
    int rows = 0;
    std::string last;
    while (std::getline(in, line)) {
      ++rows;
      last = line;
    }
    CHECK(rows == 2);
    CHECK(metrica_cli("check " + (dir / "run/loop-02.meshb")).code == 0);
    CHECK(io::read_meshb(dir / "run/loop-02.meshb").version == 3);  // --format-version
    CHECK(io::read_sol(dir / "run/loop-02.solb").version == 3);
    // `error` measures what the loop reported, and against a truth mesh:
    // zero against itself, positive against another.
    auto error_of = [](const Run& run) {
      const auto at = run.output.find("L2 error ");
      REQUIRE(at != std::string::npos);
      return std::stod(run.output.substr(at + 9));
    };
    const auto e2 = metrica_cli("error " + (dir / "run/loop-02.meshb") + " --analytic tanh3");
    INFO(e2.output);
    REQUIRE(e2.code == 0);
    const double csv_error = std::stod(last.substr(nth_comma(last, 5) + 1));
    CHECK(error_of(e2) == doctest::Approx(csv_error).epsilon(1e-5));
    const auto self = metrica_cli("error " + (dir / "run/loop-02.meshb") + " --analytic tanh3 --truth " +
                                  (dir / "run/loop-02.meshb"));
    REQUIRE(self.code == 0);
    CHECK(error_of(self) < 1e-12);
    const auto coarse = metrica_cli("error " + (dir / "run/loop-01.meshb") + " --analytic tanh3 --truth " +
                                    (dir / "run/loop-02.meshb"));
    REQUIRE(coarse.code == 0);
    CHECK(error_of(coarse) > 1e-6);
    CHECK(metrica_cli("error " + (dir / "run/loop-02.meshb")).code == 2);                      // no reference
    CHECK(metrica_cli("error " + (dir / "run/loop-02.meshb") + " --field f.solb").code == 2);  // no truth
    CHECK(metrica_cli("error " + (dir / "missing.meshb") + " --analytic tanh3").code == 1);
    // Transfer a field from iteration 1's mesh to iteration 2's.
    REQUIRE(
        metrica_cli("metric " + (dir / "run/loop-01.meshb") + " --field tanh3 --complexity 500 -o " + (dir / "m1.solb"))
            .code == 0);
    const auto m1 = io::read_meshb(dir / "run/loop-01.meshb");
    const auto m2 = io::read_meshb(dir / "run/loop-02.meshb");
    // A metric moves log-Euclidean: M = exp(L(x)) with L linear in x moves
    // exactly, and stays SPD.
    auto log_linear = [](const Point& p) {
      return spd_exp({1.0 + p.x(), 0.3 * p.y(), 2.0 - p.z(), 0.2 * p.x() - 0.1, 0.5 * p.z(), 3.0 * p.y()});
    };
    REQUIRE(metrica_cli("interpolate " + (dir / "run/loop-01.meshb") + " --field " + (dir / "m1.solb") + " --to " +
                        (dir / "run/loop-02.meshb") + " -o " + (dir / "m2.solb"))
                .code == 0);
    CHECK(io::read_sol(dir / "m2.solb").types == std::vector<io::SolType>{io::SolType::sym_matrix});
    io::write_sol(dir / "e1.solb", metric_field_to_sol([&] {
                    std::vector<Sym6> e;
                    for (const auto& p : m1.vertices) e.push_back(log_linear(p));
                    return e;
                  }()));
    const auto moved_metric =
        metrica_cli("interpolate " + (dir / "run/loop-01.meshb") + " --field " + (dir / "e1.solb") + " --to " +
                    (dir / "run/loop-02.meshb") + " -o " + (dir / "e2.sol"));
    INFO(moved_metric.output);
    REQUIRE(moved_metric.code == 0);
    const auto moved_e = metric_field_from_sol(io::read_sol(dir / "e2.sol"), m2.vertices.size(), "e2.sol");
    double metric_worst = 0;
    for (std::size_t i = 0; i < moved_e.size(); ++i)
      metric_worst = std::max(metric_worst, test::rel_diff(moved_e[i], log_linear(m2.vertices[i])));
    CHECK(metric_worst < 1e-8);
    // A tensor that is not SPD is refused, nothing written.
    io::SolData bad_metric = metric_field_to_sol(std::vector<Sym6>(m1.vertices.size(), Sym6{1, 0, -1, 0, 0, 1}));
    io::write_sol(dir / "bad.solb", bad_metric);
    const auto bad = metrica_cli("interpolate " + (dir / "run/loop-01.meshb") + " --field " + (dir / "bad.solb") +
                                 " --to " + (dir / "run/loop-02.meshb") + " -o " + (dir / "f2.solb"));
    CHECK(bad.code == 1);
    CHECK(has(bad, "not symmetric positive definite"));
    CHECK_FALSE(std::filesystem::exists(dir / "f2.solb"));
    // A linear scalar field moves exactly.
    auto linear = [](const Point& p) { return 1.0 + p.x() - 2.0 * p.y() + 3.0 * p.z(); };
    io::SolData f1;
    f1.count = m1.vertices.size();
    f1.types = {io::SolType::scalar};
    for (const auto& p : m1.vertices) f1.values.push_back(linear(p));
    io::write_sol(dir / "f1.solb", f1);
    const auto ok = metrica_cli("interpolate " + (dir / "run/loop-01.meshb") + " --field " + (dir / "f1.solb") +
                                " --to " + (dir / "run/loop-02.meshb") + " -o " + (dir / "f2.solb"));
    INFO(ok.output);
    REQUIRE(ok.code == 0);
    const auto f2 = io::read_sol(dir / "f2.solb");
    REQUIRE(f2.count == m2.vertices.size());
    double worst = 0;
    for (std::size_t i = 0; i < f2.count; ++i) worst = std::max(worst, std::abs(f2.values[i] - linear(m2.vertices[i])));
    CHECK(worst < 1e-9);
    // A solution of a vector and a scalar (a flow: velocity, pressure)
    // moves field by field, its types kept; linear fields exactly.
    io::SolData flow;
    flow.count = m1.vertices.size();
    flow.types = {io::SolType::vector, io::SolType::scalar};
    auto flow_at = [&](const Point& p) {
      return std::array<double, 4>{linear(p), 2.0 * p.x(), -p.z() + 0.5, 3.0 * p.y() - p.x()};
    };
    for (const auto& p : m1.vertices)
      for (double x : flow_at(p)) flow.values.push_back(x);
    io::write_sol(dir / "flow1.sol", flow);
    const auto moved = metrica_cli("interpolate " + (dir / "run/loop-01.meshb") + " --field " + (dir / "flow1.sol") +
                                   " --to " + (dir / "run/loop-02.meshb") + " -o " + (dir / "flow2.sol"));
    INFO(moved.output);
    REQUIRE(moved.code == 0);
    auto flow2 = io::read_sol(dir / "flow2.sol");
    REQUIRE(flow2.count == m2.vertices.size());
    CHECK(flow2.types == flow.types);
    worst = 0;
    for (std::size_t i = 0; i < flow2.count; ++i)
      for (int c = 0; c < 4; ++c)
        worst = std::max(worst, std::abs(flow2.values[4 * i + c] - flow_at(m2.vertices[i])[c]));
    CHECK(worst < 1e-9);
    // The multiscale metric of chosen fields, intersected; linear fields are
    // left out with a warning, and when all are linear it is an error.
    const auto fields = metrica_cli("metric " + (dir / "run/loop-02.meshb") + " --field-file " + (dir / "flow2.sol") +
                                    " --fields 1,2 --complexity 500 -o " + (dir / "fm.solb"));
    CHECK(fields.code == 1);
    CHECK(has(fields, "linear"));
    // A quadratic pressure: its metric, and the same with the linear
    // velocity beside it.
    for (std::size_t i = 0; i < flow2.count; ++i) {
      const Point& p = m2.vertices[i];
      flow2.values[4 * i + 3] = p.x() * p.x() + 0.5 * p.y() * p.z();
    }
    io::write_sol(dir / "flow2q.solb", flow2);
    const auto q2 = metrica_cli("metric " + (dir / "run/loop-02.meshb") + " --field-file " + (dir / "flow2q.solb") +
                                " --fields 2 --complexity 500 -o " + (dir / "q2.solb"));
    INFO(q2.output);
    REQUIRE(q2.code == 0);
    const auto q12 = metrica_cli("metric " + (dir / "run/loop-02.meshb") + " --field-file " + (dir / "flow2q.solb") +
                                 " --fields 1,2 --complexity 500 -o " + (dir / "q12.solb"));
    INFO(q12.output);
    REQUIRE(q12.code == 0);
    CHECK(has(q12, "fields 1.x, 1.y, 1.z, 2, intersected"));
    CHECK(has(q12, "zero Hessian"));
    const auto a = io::read_sol(dir / "q12.solb").values, b = io::read_sol(dir / "q2.solb").values;
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) CHECK(a[i] == doctest::Approx(b[i]).epsilon(1e-9).scale(1.0));
    CHECK(metrica_cli("metric " + (dir / "run/loop-02.meshb") + " --field-file " + (dir / "flow2q.solb") +
                      " --fields 3 -o " + (dir / "x.solb"))
              .code == 1);
    CHECK(metrica_cli("metric " + (dir / "run/loop-02.meshb") + " --field tanh3 --fields 1 -o " + (dir / "x.solb"))
              .code == 2);
    for (const char* selection : {"x", "1,", "1.w", ",2", "1..x", "-1"})
      CHECK(metrica_cli("metric " + (dir / "run/loop-02.meshb") + " --field-file " + (dir / "flow2q.solb") +
                        " --fields=" + selection + " -o " + (dir / "x.solb"))
                .code == 2);
    CHECK_FALSE(std::filesystem::exists(dir / "x.solb"));
  }

  TEST_CASE("metric of the planar front tanh(10 (x + y + z - 1.5)) on the 9x9x9 cube: a rotated rank-1 Hessian") {
    test::TempDir dir;
    REQUIRE(metrica_cli("cube --n 8 -o " + (dir / "c.meshb")).code == 0);
    const auto c = io::read_meshb(dir / "c.meshb");
    io::SolData f;
    f.count = c.vertices.size();
    f.types = {io::SolType::scalar};
    for (const auto& p : c.vertices) f.values.push_back(std::tanh(10.0 * (p.sum() - 1.5)));
    io::write_sol(dir / "f.sol", f);
    const auto r = metrica_cli("metric " + (dir / "c.meshb") + " --field-file " + (dir / "f.sol") +
                               " --complexity 2000 -o " + (dir / "m.solb"));
    INFO(r.output);
    REQUIRE(r.code == 0);
    CHECK(metric_field_from_sol(io::read_sol(dir / "m.solb"), c.vertices.size(), "m.solb").size() == f.count);
  }

  TEST_CASE("adapt on bad input: exit 1 with the reason - nothing written") {
    test::TempDir dir;
    REQUIRE(metrica_cli("cube --n 2 -o " + (dir / "c.meshb")).code == 0);
    {
      // A metric for another mesh.
      const auto r = metrica_cli("adapt " + (dir / "c.meshb") + " -m " + test::ugawg("cube-linear-00.solb") + " -o " +
                                 (dir / "a.meshb"));
      CHECK(r.code == 1);
      CHECK(has(r, "the metric has 64 entries but the mesh has 27 vertices"));
    }
    {
      // A tensor that is not positive definite.
      std::ofstream sol(dir / "bad.sol");
      sol << "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n27\n1 3\n";
      for (int i = 0; i < 27; ++i) sol << (i == 5 ? "1 0 1 0 0 -1\n" : "1 0 1 0 0 1\n");
      sol << "End\n";
    }
    {
      const auto r =
          metrica_cli("adapt " + (dir / "c.meshb") + " -m " + (dir / "bad.sol") + " -o " + (dir / "a.meshb"));
      CHECK(r.code == 1);
      CHECK(has(r, "not positive definite"));
    }
    {
      std::ofstream(dir / "inv.mesh") << "MeshVersionFormatted 2\nDimension 3\nVertices\n5\n0 0 0 0\n1 0 0 0\n"
                                         "0 1 0 0\n0 0 1 0\n0 0 -1 0\nTetrahedra\n2\n1 2 3 4 0\n1 2 3 5 0\nEnd\n";
      const auto r = metrica_cli("adapt " + (dir / "inv.mesh") + " --analytic linear -o " + (dir / "a.meshb"));
      CHECK(r.code == 1);
      CHECK(has(r, "inverted"));
    }
    CHECK(metrica_cli("adapt " + (dir / "c.meshb") + " -o " + (dir / "a.meshb")).code == 2);  // no metric
    CHECK(
        metrica_cli("adapt " + (dir / "c.meshb") + " --analytic linear --space curved -o " + (dir / "a.meshb")).code ==
        2);  // usage
    CHECK(
        metrica_cli("adapt " + (dir / "c.meshb") + " --analytic linear --points random -o " + (dir / "a.meshb")).code ==
        2);
    CHECK(metrica_cli("adapt " + (dir / "c.meshb") + " --analytic linear --repair-rounds -1 -o " + (dir / "a.meshb"))
              .code == 2);
    CHECK(metrica_cli("adapt " + (dir / "c.meshb") + " --analytic linear --repair-below 1.5 -o " + (dir / "a.meshb"))
              .code == 2);
    CHECK_FALSE(std::filesystem::exists(dir / "a.meshb"));
  }

  TEST_CASE("bad input: exit 1 with one clear message - nothing written") {
    test::TempDir dir;
    {
      std::ofstream(dir / "bad.meshb") << "this is not a mesh";
      const auto r = metrica_cli("check " + (dir / "bad.meshb"));
      CHECK(r.code == 1);
      CHECK_FALSE(r.signalled);
      CHECK(has(r, "bad magic number"));
    }
    {
      const auto r = metrica_cli("info " + (dir / "missing.meshb"));
      CHECK(r.code == 1);
      CHECK(has(r, "cannot open"));
    }
    {
      // Truncated binary file.
      const auto bytes = io::read_file_bytes(test::ugawg("cube-cylinder.meshb"));
      std::ofstream(dir / "cut.meshb", std::ios::binary) << bytes.substr(0, bytes.size() / 3);
      const auto r = metrica_cli("convert " + (dir / "cut.meshb") + " " + (dir / "out.meshb"));
      CHECK(r.code == 1);
      CHECK(has(r, "truncated"));
      CHECK_FALSE(std::filesystem::exists(dir / "out.meshb"));
    }
    {
      // An inverted tet.
      std::ofstream(dir / "inv.mesh") << "MeshVersionFormatted 2\nDimension 3\nVertices\n5\n0 0 0 0\n1 0 0 0\n"
                                         "0 1 0 0\n0 0 1 0\n0 0 -1 0\nTetrahedra\n2\n1 2 3 4 0\n1 2 3 5 0\nEnd\n";
      const auto r = metrica_cli("convert " + (dir / "inv.mesh") + " " + (dir / "inv.meshb"));
      CHECK(r.code == 1);
      CHECK(has(r, "inverted"));
      CHECK_FALSE(std::filesystem::exists(dir / "inv.meshb"));
    }
    // Only the inputs remain: no temporary files were left behind.
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
    CHECK(files == 3);
  }

  TEST_CASE("bootstrap - adapt and check on a CAD model: the boundary on the model - the association written") {
    test::TempDir dir;
    const std::string step = test::ugawg("cube-cylinder.step");
    // One thread: gmsh's meshing on two threads gives a different start
    // mesh from run to run, and with it a different adaptation.
    const auto boot = metrica_cli("bootstrap " + step + " -o " + (dir / "start.meshb") + " --size 0.25 --threads 1");
    INFO(boot.output);
    REQUIRE(boot.code == 0);
    const auto start = io::read_meshb(dir / "start.meshb");
    CHECK(!start.on_geometry[0].empty());
    CHECK(!start.on_geometry[1].empty());
    CHECK(!start.on_geometry[2].empty());
    const auto adapt =
        metrica_cli("adapt " + (dir / "start.meshb") + " --geometry " + step +
                    " --analytic polar-2 --cycles 4 --quality-passes 1" + serial_option() + " -o " + (dir / "a.meshb"));
    INFO(adapt.output);
    REQUIRE(adapt.code == 0);
    CHECK(has(adapt, "largest distance to their entity"));
    const auto adapted = io::read_meshb(dir / "a.meshb");
    CHECK(adapted.on_geometry[2].size() > start.on_geometry[2].size());
    const auto check = metrica_cli("check " + (dir / "a.meshb") + " --geometry " + step);
    INFO(check.output);
    CHECK(check.code == 0);
    CHECK(has(check, "valid"));
    // The mesh of another model: exit 1, the reason, nothing written.
    const auto wrong = metrica_cli("adapt " + (dir / "start.meshb") + " --geometry " + test::ugawg("cone-cone.step") +
                                   " --analytic polar-2 -o " + (dir / "b.meshb"));
    CHECK(wrong.code == 1);
    CHECK(has(wrong, "does not match"));
    CHECK(!std::filesystem::exists(dir / "b.meshb"));
    const auto missing = metrica_cli("check " + (dir / "a.meshb") + " --geometry " + (dir / "none.step"));
    CHECK(missing.code == 1);
    CHECK(has(missing, "no such model file"));
  }

  TEST_CASE("metric --geometry: the curved walls of the model bound the sizes - the complexity grows") {
    test::TempDir dir;
    const std::string model = std::string(METRICA_TEST_DATA_DIR) + "/channel.geo";
    REQUIRE(metrica_cli("bootstrap " + model + " -o " + (dir / "c.meshb") + " --size 0.1 --threads 1").code == 0);
    auto complexity_of = [](const Run& r) {
      const auto at = r.output.find("complexity ");
      REQUIRE(at != std::string::npos);
      return std::stod(r.output.substr(at + 11));
    };
    const auto plain =
        metrica_cli("metric " + (dir / "c.meshb") + " --analytic linear --complexity 2000 -o " + (dir / "plain.solb"));
    REQUIRE(plain.code == 0);
    const auto bounded =
        metrica_cli("metric " + (dir / "c.meshb") + " --analytic linear --complexity 2000 --geometry " + model +
                    " --curvature-angle 5 --gradation 1.5 -o " + (dir / "bounded.solb"));
    INFO(bounded.output);
    REQUIRE(bounded.code == 0);
    CHECK(has(bounded, "curved boundaries"));
    CHECK(complexity_of(bounded) > complexity_of(plain) * 1.05);
    CHECK(metrica_cli("metric " + (dir / "c.meshb") + " --analytic linear --curvature-angle 5 -o " + (dir / "x.solb"))
              .code == 2);
    CHECK(metrica_cli("metric " + (dir / "c.meshb") + " --analytic linear --geometry " + model +
                      " --curvature-angle 0 -o " + (dir / "x.solb"))
              .code == 2);
    CHECK(metrica_cli("metric " + (dir / "c.meshb") + " --analytic linear --geometry " +
                      test::ugawg("cube-cylinder.step") + " -o " + (dir / "x.solb"))
              .code == 1);  // another model's mesh
    CHECK_FALSE(std::filesystem::exists(dir / "x.solb"));
  }

  TEST_CASE("usage errors exit 2 - --help exits 0 for every command") {
    CHECK(metrica_cli("").code == 2);
    CHECK(metrica_cli("frobnicate").code == 2);
    CHECK(metrica_cli("cube --n 3").code == 2);  // no output
    CHECK(metrica_cli("cube --n 1 2 -o x.mesh").code == 2);
    CHECK(metrica_cli("check --no-such-option").code == 2);
    CHECK(metrica_cli("info --threads 0 x.mesh").code == 2);
    CHECK(metrica_cli("convert a.sol b.mesh").code == 2);
    CHECK(metrica_cli("--help").code == 0);
    CHECK(metrica_cli("metric x.meshb -o m.solb").code == 2);  // no source
    CHECK(metrica_cli("metric x.meshb --analytic linear --field tanh3 -o m.solb").code == 2);
    CHECK(metrica_cli("quality x.meshb").code == 2);  // no metric
    CHECK(metrica_cli("loop --quick").code == 2);     // no field
    CHECK(metrica_cli("loop --field tanh3 --iterations 0").code == 2);
    CHECK(metrica_cli("loop --field tanh3 --norm 0.5").code == 2);
    CHECK(metrica_cli("loop --field nofield --quick").code == 2);
    CHECK(metrica_cli("interpolate a.meshb --to b.meshb -o c.solb").code == 2);  // no field
    CHECK(metrica_cli("bootstrap model.step").code == 2);                        // no output
    CHECK(metrica_cli("bootstrap " + test::ugawg("cube-cylinder.step") + " -o x.meshb --size 0").code == 2);
    CHECK(metrica_cli("bootstrap " + test::ugawg("cube-cylinder.step") + " -o x.meshb --size 1e-9").code == 2);
    CHECK(metrica_cli("loop --field tanh3 --quick --geometry m.step").code == 2);  // no start mesh
    for (const char* c : {"cube", "bootstrap", "info", "check", "convert", "metric", "quality", "adapt", "pipeline",
                          "loop", "interpolate", "error"}) {
      const auto r = metrica_cli(std::string(c) + " --help");
      CHECK(r.code == 0);
      CHECK(has(r, "Example"));
    }
  }

  TEST_CASE("docs/cli.md lists every command and every option of the help (scripts/cli-docs writes it)") {
    std::ifstream in(std::string(METRICA_DOCS_DIR) + "/cli.md");
    REQUIRE(in.good());
    const std::string docs((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const char* cmd : {"cube", "info", "check", "convert", "metric", "adapt", "pipeline", "loop", "interpolate",
                            "error", "quality"}) {
      CAPTURE(cmd);
      CHECK(docs.find(std::string("## metrica ") + cmd + "\n") != std::string::npos);
      const auto help = metrica_cli(std::string(cmd) + " --help");
      REQUIRE(help.code == 0);
      // Every "--option" the help names.
      for (std::size_t at = help.output.find("--"); at != std::string::npos; at = help.output.find("--", at + 2)) {
        std::size_t end = at + 2;
        while (end < help.output.size() &&
               (std::isalnum(static_cast<unsigned char>(help.output[end])) || help.output[end] == '-'))
          ++end;
        if (end == at + 2) continue;
        const std::string option = help.output.substr(at, end - at);
        CAPTURE(option);
        CHECK(docs.find(option) != std::string::npos);
      }
    }
  }

  TEST_CASE("an absurd --threads is capped at 8 per core with a warning - the run succeeds") {
    test::TempDir dir;
    REQUIRE(metrica_cli("cube --n 2 -o " + (dir / "c.meshb")).code == 0);
    const auto r =
        metrica_cli("adapt " + (dir / "c.meshb") +
                    " --analytic linear --cycles 2 --quality-passes 1 --threads 100000 -o " + (dir / "a.meshb"));
    CHECK(r.code == 0);
    CHECK(has(r, "more than 8 per core"));
  }
}
