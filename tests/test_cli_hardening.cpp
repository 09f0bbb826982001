// Bad input through the `metrica` command, one case per class a user or a
// fuzzer met: every one ends with a clear message and exit 1 (bad input,
// failed run) or 2 (usage), never a signal, a NaN reported as a success or
// a damaged output.
#include "cli_test_support.hpp"
#include "test_support.hpp"

#include <metrica/io/meshb.hpp>

#include <doctest/doctest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>
#include <vector>

using namespace metrica;
using test::has;
using test::metrica_cli;
namespace fs = std::filesystem;

namespace {

// A SolAtVertices file with the same tensor at each of n vertices.
void write_uniform_metric(const std::string& path, int n, const char* tensor) {
  std::ofstream sol(path);
  sol << "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n" << n << "\n1 3\n";
  for (int i = 0; i < n; ++i) sol << tensor << "\n";
  sol << "End\n";
}

// The files of a folder whose name starts with `prefix`.
std::size_t files_starting(const std::string& folder, const std::string& prefix) {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(folder))
    if (e.path().filename().string().rfind(prefix, 0) == 0) ++n;
  return n;
}

std::string file_bytes(const std::string& path) { return io::read_file_bytes(path); }

// Two unit tets meeting at one vertex: every face on the boundary, yet the
// boundary is not a manifold (a pinched vertex).
const char* kPinched =
    "MeshVersionFormatted 2\nDimension 3\nVertices\n7\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n-1 0 0 0\n0 -1 0 0\n"
    "0 0 -1 0\nTetrahedra\n2\n1 2 3 4 0\n1 6 5 7 0\nTriangles\n8\n1 3 2 1\n1 2 4 1\n1 4 3 1\n2 3 4 1\n1 5 6 1\n"
    "1 6 7 1\n1 7 5 1\n6 5 7 1\nEnd\n";

}  // namespace

TEST_SUITE("regression") {
  TEST_CASE("metrics out of double's reach are refused - or clamped by --hmin/--hmax - never a NaN report") {
    test::TempDir dir;
    REQUIRE(metrica_cli("cube --n 2 -o " + (dir / "c.meshb")).code == 0);
    // 5.6e-307 I: sizes of 4e153, whose determinant underflows.
    write_uniform_metric(dir / "tiny.sol", 27, "5.6e-307 0 5.6e-307 0 0 5.6e-307");
    for (const char* cmd : {"quality", "adapt"}) {
      CAPTURE(cmd);
      const auto r = metrica_cli(std::string(cmd) + " " + (dir / "c.meshb") + " -m " + (dir / "tiny.sol") +
                                 (std::string(cmd) == "adapt" ? " -o " + (dir / "a.meshb") : ""));
      CHECK(r.code == 1);
      CHECK(has(r, "outside [1e-30, 1e+30]"));
      CHECK_FALSE(has(r, "nan"));
    }
    // The same with --hmax: clamped to h = 0.5, a finite report.
    const auto q = metrica_cli("quality " + (dir / "c.meshb") + " -m " + (dir / "tiny.sol") + " --hmax 0.5");
    INFO(q.output);
    CHECK(q.code == 0);
    CHECK_FALSE(has(q, "nan"));
    // Entries of 1e300: sizes of 1e-150.
    write_uniform_metric(dir / "huge.sol", 27, "1e300 0 1e300 0 0 1e300");
    const auto h = metrica_cli("adapt " + (dir / "c.meshb") + " -m " + (dir / "huge.sol") + " -o " + (dir / "a.meshb"));
    CHECK(h.code == 1);
    CHECK(has(h, "outside"));
    write_uniform_metric(dir / "nan.sol", 27, "nan 0 1 0 0 1");
    CHECK(metrica_cli("quality " + (dir / "c.meshb") + " -m " + (dir / "nan.sol")).code == 1);
    CHECK_FALSE(fs::exists(dir / "a.meshb"));
  }

  TEST_CASE("coordinates beyond 1e12 or not finite are refused by every command that reads a mesh") {
    test::TempDir dir;
    for (const char* x : {"1e308", "nan", "inf", "2e12"}) {
      CAPTURE(x);
      std::ofstream(dir / "far.mesh") << "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n"
                                      << x << " 0 0 0\n0 1 0 0\n0 0 1 0\nTetrahedra\n1\n1 2 3 4 0\nEnd\n";
      for (const std::string& cmd :
           std::vector<std::string>{"info", "check", "adapt --analytic linear -o " + (dir / "a.meshb"),
                                    "metric --analytic linear -o " + (dir / "m.solb")}) {
        CAPTURE(cmd);
        const auto r = metrica_cli(cmd.substr(0, cmd.find(' ')) + " " + (dir / "far.mesh") +
                                   (cmd.find(' ') == std::string::npos ? "" : cmd.substr(cmd.find(' '))));
        CHECK(r.code == 1);
        CHECK(has(r, "vertex 2 has coordinates"));
      }
    }
    // interpolate to a target with a NaN coordinate.
    REQUIRE(metrica_cli("cube --n 2 -o " + (dir / "c.meshb")).code == 0);
    REQUIRE(metrica_cli("metric " + (dir / "c.meshb") + " --field tanh3 -o " + (dir / "f.solb")).code == 0);
    std::ofstream(dir / "to.mesh") << "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\nnan 0 0 0\n"
                                      "0 1 0 0\n0 0 1 0\nTetrahedra\n1\n1 2 3 4 0\nEnd\n";
    const auto r = metrica_cli("interpolate " + (dir / "c.meshb") + " --field " + (dir / "f.solb") + " --to " +
                               (dir / "to.mesh") + " -o " + (dir / "out.solb"));
    CHECK(r.code == 1);
    CHECK_FALSE(fs::exists(dir / "out.solb"));
  }

  TEST_CASE("an invalid input mesh is refused before any work - a non-manifold or open boundary") {
    test::TempDir dir;
    std::ofstream(dir / "pinched.mesh") << kPinched;
    // A boundary given in part as triangles (all of it or none is taken).
    std::ofstream(dir / "open.mesh") << "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n"
                                        "0 1 0 0\n0 0 1 0\nTriangles\n1\n1 3 2 1\nTetrahedra\n1\n1 2 3 4 0\nEnd\n";
    for (const char* input : {"pinched.mesh", "open.mesh"}) {
      CAPTURE(input);
      const auto adapt = metrica_cli("adapt " + (dir / input) + " --analytic linear -o " + (dir / "a.meshb"));
      INFO(adapt.output);
      CHECK(adapt.code == 1);
      CHECK(has(adapt, std::string(input) == "open.mesh" ? "have no input triangle" : "not form a single umbrella"));
      CHECK_FALSE(has(adapt, "cycle"));  // refused before the first cycle
      const auto loop = metrica_cli("loop --field tanh3 --quick -i " + (dir / input));
      CHECK(loop.code == 1);
      CHECK_FALSE(has(loop, "complexity"));
    }
    CHECK(metrica_cli("check " + (dir / "pinched.mesh")).code == 1);
    CHECK_FALSE(fs::exists(dir / "a.meshb"));
  }

  TEST_CASE("a run predicted beyond --max-tets is refused with the prediction - --dry-run reports it") {
    test::TempDir dir;
    REQUIRE(metrica_cli("cube --n 2 -o " + (dir / "c.meshb")).code == 0);
    const auto refused =
        metrica_cli("adapt " + (dir / "c.meshb") + " --analytic linear --max-tets 1000 -o " + (dir / "a.meshb"));
    CHECK(refused.code == 1);
    CHECK(has(refused, "the limit is 1e+03 tets"));
    const auto dry = metrica_cli("adapt " + (dir / "c.meshb") + " --analytic linear --dry-run -o " + (dir / "a.meshb"));
    CHECK(dry.code == 0);
    CHECK(has(dry, "tets out"));
    CHECK_FALSE(fs::exists(dir / "a.meshb"));
    // The loop's last iteration and a metric's target.
    CHECK(metrica_cli("loop --field tanh3 --complexity 1e12 --iterations 1").code == 1);
    const auto metric =
        metrica_cli("metric " + (dir / "c.meshb") + " --analytic linear --complexity 1e300 -o " + (dir / "m.solb"));
    CHECK(metric.code == 1);
    CHECK(has(metric, "--max-tets"));
    CHECK_FALSE(fs::exists(dir / "m.solb"));
  }

  TEST_CASE("options out of their domain are usage errors (exit 2) found before any input is read") {
    // The input does not exist: a usage error must be found first.
    const std::string in = "/nonexistent/in.meshb", out = " -o /tmp/out.meshb";
    for (const std::string& args : std::vector<std::string>{
             "adapt " + in + " --analytic linear --shape-floor nan" + out,
             "adapt " + in + " --analytic linear --shape-floor 2" + out,
             "adapt " + in + " --analytic linear --smooth-below -5" + out,
             "adapt " + in + " --analytic linear --collapse-max-length -1" + out,
             "adapt " + in + " --analytic linear --cycles 2.5" + out,
             "adapt " + in + " --analytic linear --quality-passes 1001" + out,
             "adapt " + in + " --analytic linear --max-length 0" + out, "loop --field tanh3 --smooth-below 1.5",
             "adapt " + in + " --analytic linear --min-length 2 --max-length 1" + out,
             "adapt " + in + " --analytic linear --space curved" + out,
             "adapt " + in + " --analytic linear --points random" + out, "adapt " + in + " --analytic nope" + out,
             "adapt " + in + " --analytic linear --hmin 2 --hmax 1" + out,
             "adapt " + in + " --analytic linear --format-version 7" + out,
             "adapt " + in + " --analytic linear -o /tmp/out.txt",
             "adapt " + in + " --analytic linear --metric-out m.mesh" + out, "cube --n 0" + out,
             "cube --n 2 --hi=1e308,1,1" + out, "cube --n 2 --hi=inf,1,1" + out,
             "cube --n 2 --lo=1,0,0 --hi=0,1,1" + out,
             "metric " + in + " --analytic linear --complexity 0 -o /tmp/m.solb",
             "metric " + in + " --analytic linear --complexity nan -o /tmp/m.solb",
             "metric " + in + " --field tanh3 --norm 0.5 -o /tmp/m.solb",
             "metric " + in + " --analytic linear --gradation-space curved -o /tmp/m.solb",
             "metric " + in + " --analytic linear -o /tmp/m.meshb", "check " + in + " --max-messages -3",
             "check " + in + " --model-tolerance -1", "loop --field nofield --quick",
             "loop --field tanh3 --complexity inf", "loop --field tanh3 --gradation 0.5",
             "quality " + in + " --analytic linear --space curved", "error " + in + " --analytic nofield",
             "convert " + in + " /tmp/out.obj", "interpolate " + in + " --field f.solb --to t.meshb -o out.meshb",
             // A value-taking option followed by another option: the fuzzer's
             // `--ou --dry-run` ran the whole loop into a folder "--dry-run".
             "loop --field tanh3 -i " + in + " --quick --output-dir --dry-run",
             "loop --field tanh3 -i " + in + " --quick --ou --dry-run",
             "adapt " + in + " --analytic linear -o --dry-run", "metric " + in + " --analytic linear -o --quiet",
             // Boost's placeholder in a bad value: its message looped forever.
             "cube --n %value%" + out, "cube --n 2 --lo %canonical_option%" + out}) {
      CAPTURE(args);
      const auto r = metrica_cli(args);
      CHECK(r.code == 2);
      CHECK_FALSE(has(r, "cannot open"));
    }
  }

  TEST_CASE("outputs are checked before any work - read-only refused - symlink followed - mode kept") {
    test::TempDir dir;
    REQUIRE(metrica_cli("cube --n 2 -o " + (dir / "c.meshb")).code == 0);
    // A missing folder for -o or --csv: exit 1 before the input is read.
    const auto missing = metrica_cli("cube --n 2 -o " + (dir / "no/such/folder.meshb"));
    CHECK(missing.code == 1);
    CHECK(has(missing, "cannot write into folder"));
    CHECK(metrica_cli("quality /nonexistent.meshb --analytic linear --csv " + (dir / "no/q.csv")).code == 1);
    // Read-only: refused, left as it was.
    REQUIRE(metrica_cli("cube --n 1 -o " + (dir / "ro.meshb")).code == 0);
    ::chmod((dir / "ro.meshb").c_str(), 0444);
    const auto before = file_bytes(dir / "ro.meshb");
    const auto ro = metrica_cli("cube --n 2 -o " + (dir / "ro.meshb"));
    CHECK(ro.code == 1);
    CHECK(has(ro, "read-only"));
    CHECK(file_bytes(dir / "ro.meshb") == before);
    // A symlink: its target is replaced, the link stays, the mode is kept.
    REQUIRE(metrica_cli("cube --n 1 -o " + (dir / "real.meshb")).code == 0);
    ::chmod((dir / "real.meshb").c_str(), 0640);
    fs::create_symlink("real.meshb", dir / "link.meshb");
    REQUIRE(metrica_cli("cube --n 2 -o " + (dir / "link.meshb")).code == 0);
    CHECK(fs::is_symlink(dir / "link.meshb"));
    CHECK(io::read_meshb(dir / "real.meshb").tets.size() == 48);
    struct stat st {};
    REQUIRE(::stat((dir / "real.meshb").c_str(), &st) == 0);
    CHECK((st.st_mode & 0777) == 0640);
    // A FIFO is not replaced by a file.
    REQUIRE(::mkfifo((dir / "fifo.meshb").c_str(), 0644) == 0);
    CHECK(metrica_cli("cube --n 2 -o " + (dir / "fifo.meshb")).code == 1);
    CHECK(fs::is_fifo(dir / "fifo.meshb"));
    // A long but legal name (255 bytes): the temporary's name is short.
    const std::string long_name = std::string(249, 'x') + ".meshb";
    CHECK(metrica_cli("cube --n 1 -o " + (dir / long_name)).code == 0);
    CHECK(fs::exists(dir / long_name));
    // No temporary left.
    CHECK(files_starting(dir.path().string(), ".metrica-") == 0);
  }

  TEST_CASE("the outputs of a run replace their targets together - a failed one replaces none") {
    test::TempDir dir;
    REQUIRE(metrica_cli("cube --n 2 -o " + (dir / "c.meshb")).code == 0);
    REQUIRE(metrica_cli("cube --n 1 -o " + (dir / "a.meshb")).code == 0);
    const auto before = file_bytes(dir / "a.meshb");
    // The adaptation succeeds, but its metric output cannot be written (its
    // name is taken by a folder that appears after the checks): the mesh
    // output stays as it was.
    fs::create_directory(dir / "m.solb");
    const auto r = metrica_cli("adapt " + (dir / "c.meshb") + " --analytic linear --cycles 1 --quality-passes 0 -o " +
                               (dir / "a.meshb") + " --metric-out " + (dir / "m.solb"));
    CHECK(r.code == 1);
    CHECK(file_bytes(dir / "a.meshb") == before);
    CHECK(files_starting(dir.path().string(), ".metrica-") == 0);
  }

  TEST_CASE("SIGTERM during a run removes its temporaries - the targets are untouched") {
    test::TempDir dir;
    const std::string out = dir / "out";
    // The loop stages each iteration's mesh while it runs; stop it after the first.
    const std::string cmd = std::string(METRICA_CLI) + " loop --field tanh3 --complexity 1000 --iterations 60 " +
                            test::serial_option() + " -q --output-dir " + out;
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      ::execl("/bin/sh", "sh", "-c", ("exec " + cmd).c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    bool staged = false;
    for (int i = 0; i < 2400 && !staged; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      staged = fs::exists(out) && files_starting(out, ".metrica-") > 0;
    }
    CHECK(staged);
    ::kill(child, SIGTERM);
    int status = 0;
    ::waitpid(child, &status, 0);
    CHECK(WIFSIGNALED(status));
    CHECK(files_starting(out, ".metrica-") == 0);
    CHECK(files_starting(out, "loop-") == 0);
  }
}
