// What an adapted mesh must be before it is kept (require_adapted), and
// what follows when a run on threads fails it (adapt_or_again_serially).
#include <metrica/box.hpp>
#include <metrica/pipeline/adapted_check.hpp>

#include <doctest/doctest.h>

#include <string>
#include <vector>

using namespace metrica;

TEST_SUITE("unit") {
  TEST_CASE("require_adapted keeps a valid mesh of the volume and refuses another volume as NotAdapted") {
    const Mesh box = make_box({.nx = 3, .ny = 3, .nz = 3});
    CHECK_NOTHROW(require_adapted(box, nullptr, 1.0, 1e-9));
    CHECK_THROWS_AS(require_adapted(box, nullptr, 1.01, 1e-3), NotAdapted);
    try {
      require_adapted(box, nullptr, 1.01, 1e-3);
    } catch (const NotAdapted& e) {
      CHECK(std::string(e.what()).find("nothing written") != std::string::npos);
    }
    // Compounded per adaptation, with room for round-off.
    CHECK(adapted_volume_tolerance(1, 1e-4) > 1e-4);
    CHECK(adapted_volume_tolerance(2, 1e-4) > 2e-4);
    CHECK(adapted_volume_tolerance(1, 0.0) > 0.0);
  }

  TEST_CASE("a threaded run that fails its end check is made again serially - a serial one is not") {
    PolicyChoice threads;
    threads.concurrency = std::string(Speculative::name);
    std::vector<std::string> runs;
    // Fails under threads, passes serially: the serial result comes back.
    const int result = adapt_or_again_serially(threads, "again", [&](const PolicyChoice& p) {
      runs.push_back(p.concurrency);
      if (p.concurrency != Serial::name) throw NotAdapted("adapt: the boundary is not on the model; nothing written");
      return 7;
    });
    CHECK(result == 7);
    CHECK(runs == std::vector<std::string>{std::string(Speculative::name), std::string(Serial::name)});

    // A serial run's failure is the caller's: no second run.
    runs.clear();
    PolicyChoice serial;
    serial.concurrency = std::string(Serial::name);
    const auto fail = [&](const PolicyChoice& p) -> int {
      runs.push_back(p.concurrency);
      throw NotAdapted("adapt: the adapted mesh is invalid; nothing written");
    };
    CHECK_THROWS_AS(adapt_or_again_serially(serial, "again", fail), NotAdapted);
    CHECK(runs.size() == 1);
    // Threads, then serial, both failing: the serial run's error.
    runs.clear();
    CHECK_THROWS_AS(adapt_or_again_serially(threads, "again", fail), NotAdapted);
    CHECK(runs.size() == 2);

    // Any other error (a bad metric, a bad file) is not a failed end check.
    runs.clear();
    const auto bad_input = [&](const PolicyChoice& p) -> int {
      runs.push_back(p.concurrency);
      throw InputError("metric: the tensor at vertex 3 is not symmetric positive definite");
    };
    CHECK_THROWS_AS(adapt_or_again_serially(threads, "again", bad_input), InputError);
    CHECK(runs.size() == 1);
  }
}
