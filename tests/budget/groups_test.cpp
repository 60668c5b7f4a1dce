// Groups of contributors: every level's variance is the sum of its members'
// (over the grid and per band), the tree is ordered depth first, the top
// level and the ungrouped terms add up to the output; bad group names and
// unknown sub-trees are errors.
#include "deb/budget/groups.h"

#include <doctest/doctest.h>

#include <cmath>

#include "deb/core/error.h"

namespace deb {
namespace {

// An output with five contributors of variances 1, 2, 4, 8, 16 in the
// groups a/b, a, (none), c/d/e, c, and two bands splitting each 1:3.
OutputResult SampleOutput() {
  OutputResult o;
  const std::vector<std::pair<std::string, std::string>> terms = {
      {"t1", "a/b"}, {"t2", "a"}, {"t3", ""}, {"t4", "c/d/e"}, {"t5", "c"}};
  double v = 1.0;
  o.bands.resize(2);
  for (const auto& [name, group] : terms) {
    ContributorResult c;
    c.name = name;
    c.group = group;
    c.variance = v;
    o.contributors.push_back(c);
    o.variance += v;
    o.bands[0].contributor_variance.push_back(0.25 * v);
    o.bands[1].contributor_variance.push_back(0.75 * v);
    v *= 2.0;
  }
  return o;
}

}  // namespace

TEST_CASE("each group holds the sum of its members at every level, depth first") {
  const OutputResult o = SampleOutput();
  const std::vector<GroupResult> g = ComputeGroups(o);
  REQUIRE(g.size() == 5);
  const std::vector<std::string> order = {"a", "a/b", "c", "c/d", "c/d/e"};
  for (std::size_t i = 0; i < g.size(); ++i) CHECK(g[i].path == order[i]);
  CHECK(g[0].variance == 3.0);   // t1 (in a/b) + t2
  CHECK(g[1].variance == 1.0);
  CHECK(g[2].variance == 24.0);  // t4 (in c/d/e) + t5
  CHECK(g[3].variance == 8.0);
  CHECK(g[4].variance == 8.0);
  CHECK(g[1].name == "b");
  CHECK(g[4].depth == 2);
  CHECK(g[0].contributors == std::vector<std::size_t>{1});
  CHECK(g[0].subgroups == std::vector<std::string>{"a/b"});
  CHECK(g[0].all_contributors == std::vector<std::size_t>{0, 1});
  CHECK(g[2].share == doctest::Approx(24.0 / 31.0).epsilon(1e-15));
  // The top level and the ungrouped term add up to the output, in every band too.
  CHECK(g[0].variance + g[2].variance + o.contributors[2].variance == o.variance);
  for (std::size_t b = 0; b < 2; ++b) {
    const double band_total = o.bands[b].contributor_variance[0] + o.bands[b].contributor_variance[1] +
                              o.bands[b].contributor_variance[2] + o.bands[b].contributor_variance[3] +
                              o.bands[b].contributor_variance[4];
    CHECK(g[0].band_variance[b] + g[2].band_variance[b] + o.bands[b].contributor_variance[2] == band_total);
  }
  // No groups named: none.
  OutputResult flat = o;
  for (ContributorResult& c : flat.contributors) c.group.clear();
  CHECK(ComputeGroups(flat).empty());
}

TEST_CASE("group names: segments between '/', no empty or reserved ones, bounded depth") {
  CHECK(GroupSegments("stage/amplifier") == std::vector<std::string>{"stage", "amplifier"});
  CHECK(GroupSegments("x-axis drive.v2") == std::vector<std::string>{"x-axis drive.v2"});
  CHECK_THROWS_AS(GroupSegments("stage//amplifier"), InputError);
  CHECK_THROWS_AS(GroupSegments("/stage"), InputError);
  CHECK_THROWS_AS(GroupSegments("stage/"), InputError);
  CHECK_THROWS_AS(GroupSegments("stage/total"), InputError);
  CHECK_THROWS_AS(GroupSegments("st@ge"), InputError);
  CHECK_THROWS_AS(GroupSegments(" stage"), InputError);
  std::string deep = "g";
  for (int i = 0; i < 16; ++i) deep += "/g";
  CHECK_THROWS_AS(GroupSegments(deep), InputError);
}

TEST_CASE("a sub-tree keeps the contributors in the group and below it; an unknown group names the nearest") {
  Budget b;
  for (const auto& [name, group] : std::vector<std::pair<std::string, std::string>>{
           {"amp", "stage/drive"}, {"cable", "stage"}, {"floor", "environment"}, {"other", ""}, {"st", "stagex"}}) {
    Contributor c;
    c.name = name;
    c.group = group;
    b.contributors.push_back(c);
  }
  const Budget stage = SelectGroup(b, "stage");
  REQUIRE(stage.contributors.size() == 2);  // not "stagex": a group is a whole segment
  CHECK(stage.contributors[0].name == "amp");
  CHECK(stage.contributors[1].name == "cable");
  CHECK(SelectGroup(b, "stage/drive").contributors.size() == 1);
  try {
    SelectGroup(b, "stag/drive");
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("did you mean 'stage/drive'?") != std::string::npos);
    CHECK(std::string(e.what()).find("the groups: stage, stage/drive, environment, stagex") != std::string::npos);
  }
}

}  // namespace deb
