#include "deb/budget/isolation_paths.h"

#include <doctest/doctest.h>

#include <string>

#include "deb/core/error.h"
#include "deb/models/isolation_model.h"
#include "tests/support/thesis_layout.h"

namespace deb {
namespace {

IsolationPathsSpec Thesis(bool control) {
  IsolationPathsSpec spec;
  spec.name = "avis";
  spec.system = ThesisCaseStudy();
  spec.units = {"mm", "t", "N"};
  spec.control = control;
  spec.key_path = "paths[0]";
  spec.control_key_path = "paths[0].control";
  return spec;
}

std::string Names(const IsolationPaths& built) {
  std::string names;
  for (const Path& p : built.paths) names += p.name + " ";
  return names;
}

TEST_CASE("the thesis model yields open- and closed-loop paths with the model's units") {
  const IsolationPaths built = MakeIsolationPaths(Thesis(true));
  CHECK(Names(built) == "avis.floor_open avis.actuator_open avis.floor avis.sensor_noise avis.actuator ");
  const Path& noise = built.paths[3];
  CHECK(noise.input_names.size() == ThesisGeophones().size());
  CHECK(noise.input_units == std::vector<std::string>(noise.input_names.size(), "mm/s"));
  CHECK(noise.output_units == std::vector<std::string>{"mm/s", "mm/s", "mm/s", "rad/s", "rad/s", "rad/s"});
  CHECK(built.paths[4].input_units.front() == "N");
  CHECK(built.report().find("model avis (units: length mm, mass t, force N)\n") == 0);
  // The paths are the model's transfers themselves.
  const IsolationModel model(ThesisCaseStudy());
  const StateSpace floor = model.FloorToCog(IsolationModel::Loop::kClosed);
  CHECK(built.paths[2].system.A() == floor.A());
  CHECK(built.paths[2].system.C() == floor.C());
  for (const Path& p : built.paths) CHECK_NOTHROW(p.Validate());
}

TEST_CASE("without a control section only the open-loop paths are formed") {
  CHECK(Names(MakeIsolationPaths(Thesis(false))) == "avis.floor_open avis.actuator_open ");
}

TEST_CASE("model errors are at the model's key path, closed-loop errors at its control") {
  IsolationPathsSpec bad = Thesis(true);
  bad.system.body.mass = 0.0;
  try {
    MakeIsolationPaths(bad);
    FAIL("a massless body must be refused");
  } catch (const InputError& e) {
    CHECK(e.key_path() == "paths[0]");
  }
  IsolationPathsSpec unstable = Thesis(true);
  unstable.system.control.gains.setConstant(-50.0);
  try {
    MakeIsolationPaths(unstable);
    FAIL("an unstable loop must be refused");
  } catch (const InputError& e) {
    CHECK(e.key_path() == "paths[0].control");
    CHECK(std::string(e.what()).find("is not stable") != std::string::npos);
  }
}

TEST_CASE("the unit set must satisfy mass = force s^2 / length") {
  CHECK_NOTHROW(CheckIsolationUnits({"mm", "t", "N"}));
  CHECK_NOTHROW(CheckIsolationUnits({}));
  CHECK_THROWS_WITH_AS(CheckIsolationUnits({"mm", "kg", "N"}),
                       "units are not one consistent set: 1 kg must equal 1 N s^2/mm (e.g. kg with m and N, or t "
                       "with mm and N)",
                       InputError);
}

}  // namespace
}  // namespace deb
