#include "deb/models/isolation_system.h"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "deb/core/error.h"
#include "tests/support/thesis_layout.h"

namespace deb {

TEST_CASE("the thesis case study is a valid system") {
  CHECK_NOTHROW(ThesisCaseStudy().Validate());
  ThesisGeometry flat;
  flat.h = 0.0;
  CHECK_NOTHROW(ThesisCaseStudy(flat).Validate());
}

TEST_CASE("the body must have positive mass and a symmetric positive definite inertia") {
  IsolationSystem s = ThesisCaseStudy();
  SUBCASE("zero mass") {
    s.body.mass = 0.0;
    CHECK_THROWS_WITH_AS(s.Validate(), "body.mass: 0 must be finite and > 0", InputError);
  }
  SUBCASE("negative mass") {
    s.body.mass = -2.1;
    CHECK_THROWS_WITH_AS(s.Validate(), "body.mass: -2.1 must be finite and > 0", InputError);
  }
  SUBCASE("indefinite inertia") {
    s.body.inertia(2, 2) = -6.4e5;
    CHECK_THROWS_WITH_AS(s.Validate(),
                         "body.inertia: must be positive definite; smallest principal moment is "
                         "-640000",
                         InputError);
  }
  SUBCASE("singular inertia") {
    s.body.inertia.setZero();
    s.body.inertia(0, 0) = 1.0;
    CHECK_THROWS_WITH_AS(s.Validate(), doctest::Contains("body.inertia: must be positive definite"),
                         InputError);
  }
  SUBCASE("asymmetric inertia") {
    s.body.inertia(0, 1) = 1e4;
    CHECK_THROWS_WITH_AS(s.Validate(), "body.inertia: must be symmetric (J_ij = J_ji)", InputError);
  }
  SUBCASE("negative gravity") {
    s.body.gravity = -9810.0;
    CHECK_THROWS_WITH_AS(s.Validate(), doctest::Contains("body.gravity: -9810 must be"), InputError);
  }
}

TEST_CASE("at least three isolators, not all on one line, must carry the body") {
  IsolationSystem s = ThesisCaseStudy();
  SUBCASE("two isolators") {
    s.isolators.resize(2);
    s.sensors.clear();
    s.actuators.clear();
    s.control = SkyhookControl{};
    CHECK_THROWS_WITH_AS(s.Validate(),
                         "isolators: need at least 3 (not all on one line) to carry the body, got 2",
                         InputError);
  }
  SUBCASE("four on one line seen from above, at different heights") {
    for (std::size_t i = 0; i < 4; ++i)
      s.isolators[i].position = Eigen::Vector3d(100.0 * i - 150.0, 2.0 * (100.0 * i - 150.0), -50.0 * i);
    CHECK_THROWS_WITH_AS(s.Validate(), doctest::Contains("isolators: the supports must not all lie on one line"),
                         InputError);
  }
  SUBCASE("three on a triangle are enough") {
    s.isolators.resize(3);
    s.sensors.clear();
    s.actuators.clear();
    s.control = SkyhookControl{};
    CHECK_NOTHROW(s.Validate());
  }
}

TEST_CASE("isolator fields are checked and named by their path") {
  IsolationSystem s = ThesisCaseStudy();
  SUBCASE("non-finite position") {
    s.isolators[2].position.y() = std::numeric_limits<double>::infinity();
    CHECK_THROWS_WITH_AS(s.Validate(), "isolators[2].position: (-615, inf, -210) must be finite",
                         InputError);
  }
  SUBCASE("vertical stiffness must be positive") {
    s.isolators[1].stiffness.z() = 0.0;
    CHECK_THROWS_WITH_AS(s.Validate(),
                         "isolators[1].stiffness: k_r = 0 must be > 0 (the vertical springs carry "
                         "the body)",
                         InputError);
  }
  SUBCASE("negative net horizontal stiffness is allowed (an unstable passive system)") {
    s.isolators[1].stiffness.x() = -3.0;
    CHECK_NOTHROW(s.Validate());
  }
  SUBCASE("negative damping") {
    s.isolators[3].damping.y() = -0.1;
    CHECK_THROWS_WITH_AS(s.Validate(), "isolators[3].damping: (0.1, -0.1, 0.1) must be finite and >= 0",
                         InputError);
  }
  SUBCASE("spring length must be positive when given") {
    s.isolators[0].spring_length = 0.0;
    CHECK_THROWS_WITH_AS(s.Validate(), "isolators[0].spring_length: 0 must be > 0", InputError);
  }
  SUBCASE("duplicate names") {
    s.isolators[3].name = "P1";
    CHECK_THROWS_WITH_AS(s.Validate(), "isolators[3].name: 'P1' is used twice; names must be unique",
                         InputError);
  }
}

TEST_CASE("sensors and actuators must name a known isolator") {
  IsolationSystem s = ThesisCaseStudy();
  SUBCASE("sensor") {
    s.sensors[4].isolator = "P9";
    CHECK_THROWS_WITH_AS(s.Validate(),
                         "sensors[4].isolator: 'P9' names no isolator (known: P1, P2, P3, P4)",
                         InputError);
  }
  SUBCASE("actuator") {
    s.actuators[0].isolator = "";
    CHECK_THROWS_WITH_AS(s.Validate(),
                         "actuators[0].isolator: '' names no isolator (known: P1, P2, P3, P4)",
                         InputError);
  }
}

TEST_CASE("given sensing and motor matrices must fit the sensors and actuators") {
  IsolationSystem s = ThesisCaseStudy();
  SUBCASE("F") {
    s.sensors.pop_back();
    CHECK_THROWS_WITH_AS(s.Validate(),
                         "control.sensing: must be 6 x 6 (logical axes x sensors), got 6 x 7",
                         InputError);
  }
  SUBCASE("M") {
    s.control.motor = s.control.motor.transpose().eval();
    CHECK_THROWS_WITH_AS(s.Validate(),
                         "control.motor: must be 8 x 6 (actuators x logical axes), got 6 x 8",
                         InputError);
  }
  SUBCASE("gain") {
    s.control.gains(4) = std::nan("");
    CHECK_THROWS_WITH_AS(s.Validate(), "control.gains[4]: nan must be finite", InputError);
  }
}

TEST_CASE("axis names parse and print both ways and unknown ones list the allowed values") {
  for (BodyAxis a : {BodyAxis::kX, BodyAxis::kY, BodyAxis::kZ}) CHECK(ParseBodyAxis(ToString(a)) == a);
  for (LocalAxis a : {LocalAxis::kP, LocalAxis::kQ, LocalAxis::kR})
    CHECK(ParseLocalAxis(ToString(a)) == a);
  CHECK_THROWS_WITH_AS(ParseBodyAxis("alpha"), "unknown body axis 'alpha'; allowed: x, y, z", InputError);
  CHECK_THROWS_WITH_AS(ParseLocalAxis("x"), "unknown isolator axis 'x'; allowed: p, q, r", InputError);
}

}  // namespace deb
