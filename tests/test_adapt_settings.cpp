// The settings table the command and Python take their adaptation options
// from (pipeline/adapt_settings.hpp): every row's default lies in its own
// domain, each row sets the member it reads, names are found in either
// spelling, and the domains refuse what they say they refuse.
#include <metrica/error.hpp>
#include <metrica/pipeline/adapt.hpp>
#include <metrica/pipeline/adapt_settings.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

using namespace metrica;

TEST_SUITE("unit") {
  TEST_CASE("each setting's default is in its domain and a value set is the value read back, alone") {
    const AdaptOptions defaults;
    std::set<std::string> names;
    for (const AdaptSetting& s : adapt_settings()) {
      CAPTURE(std::string(s.name));
      CHECK(names.insert(std::string(s.name)).second);
      CHECK(s.accepts(s.get(defaults)));
      // A value in the domain other than the default, set and read back;
      // no other row's value moves.
      const double x = s.integer ? s.get(defaults) + 1 : (s.get(defaults) + s.hi) / 2;
      REQUIRE(s.accepts(x));
      AdaptOptions o;
      s.set(o, x);
      CHECK(s.get(o) == x);
      for (const AdaptSetting& other : adapt_settings())
        if (other.name != s.name) CHECK(other.get(o) == other.get(defaults));
    }
  }

  TEST_CASE("settings are found by the command's name and by Python's - their domains refuse what they name") {
    REQUIRE(adapt_setting("quality-passes"));
    REQUIRE(adapt_setting("quality_passes"));
    CHECK(adapt_setting("quality_passes")->name == "quality-passes");
    CHECK(adapt_setting("quality_passes")->python_name() == "quality_passes");
    CHECK_FALSE(adapt_setting("passes"));
    CHECK(adapt_setting_names().find("smooth_below") != std::string::npos);
    const auto cycles = *adapt_setting("cycles");
    CHECK(cycles.domain() == "an integer in [0, 1000]");
    CHECK_FALSE(cycles.accepts(2.5));
    CHECK_FALSE(cycles.accepts(-1));
    CHECK_FALSE(cycles.accepts(std::numeric_limits<double>::quiet_NaN()));
    const auto max_length = *adapt_setting("max-length");
    CHECK(max_length.domain() == "in (0, 1000000]");
    CHECK_FALSE(max_length.accepts(0.0));
    CHECK_FALSE(max_length.accepts(std::numeric_limits<double>::infinity()));
    CHECK(max_length.accepts(1e-9));
    AdaptOptions o;
    CHECK_NOTHROW(check_length_band(o, "min", "max"));
    o.collapse.min_length = o.refine.max_length;
    CHECK_THROWS_AS(check_length_band(o, "min", "max"), InputError);
  }
}
