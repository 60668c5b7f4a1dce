#include "deb/budget/sweep.h"

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "deb/core/error.h"

namespace deb {

TEST_CASE("a grid sweep holds every combination with the last parameter fastest; a zip pairs values") {
  SweepSpec s;
  s.parameters = {{"a", {1, 2}, {}, {}, {}, {}}, {"b", {10, 20, 30}, {}, {}, {}, {}}};
  const auto grid = s.Variants();
  REQUIRE(grid.size() == 6);
  CHECK(grid[0] == std::vector<double>{1, 10});
  CHECK(grid[2] == std::vector<double>{1, 30});
  CHECK(grid[3] == std::vector<double>{2, 10});
  CHECK(grid[5] == std::vector<double>{2, 30});
  s.mode = SweepMode::kZip;
  s.parameters[1].values.pop_back();
  const auto zip = s.Variants();
  REQUIRE(zip.size() == 2);
  CHECK(zip[1] == std::vector<double>{2, 20});
}

TEST_CASE("linear and log ranges include both ends and reject empty or non-positive ranges") {
  CHECK(LinearRange(0, -300, 7) == std::vector<double>{0, -50, -100, -150, -200, -250, -300});
  CHECK(LinearRange(5, 9, 1) == std::vector<double>{5});
  const auto l = LogRange(1, 1000, 4);
  REQUIRE(l.size() == 4);
  CHECK(l[1] == doctest::Approx(10).epsilon(1e-14));
  CHECK(l[3] == 1000);
  CHECK_THROWS_WITH_AS(LinearRange(0, 1, 0), doctest::Contains("count >= 1"), InputError);
  CHECK_THROWS_WITH_AS(LogRange(0, 1, 3), doctest::Contains("ends > 0"), InputError);
  CHECK_THROWS_WITH_AS(ParseSweepMode("cartesian"), doctest::Contains("allowed: grid, zip"), InputError);
}

TEST_CASE("a sweep whose variants fail to load reports the first variant's error on any thread count") {
  SweepSpec spec;
  spec.parameters.push_back({"sources[0].spectrum.level", {1, 2, 3, 4, 5, 6, 7, 8}, {}, {}, {}, {}});
  for (int threads : {1, 2, 5}) {
    CAPTURE(threads);
    CHECK_THROWS_WITH_AS(EvaluateSweep(
                             spec,
                             [](std::size_t i) -> Budget {
                               throw InputError("variant " + std::to_string(i + 1) + " cannot load");
                             },
                             threads),
                         "variant 1 cannot load", InputError);
  }
}

}  // namespace deb
