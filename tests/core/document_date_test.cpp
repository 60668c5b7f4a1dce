// deb/core/document_date.h: $SOURCE_DATE_EPOCH dates a document when it is a
// whole number, and is ignored otherwise; UTC text of a known instant.
#include "deb/core/document_date.h"

#include <doctest/doctest.h>

#include <cstdlib>
#include <string>

namespace deb {
namespace {

// Sets SOURCE_DATE_EPOCH for one scope and puts back what was there.
class Epoch {
 public:
  explicit Epoch(const char* value) {
    if (const char* old = std::getenv("SOURCE_DATE_EPOCH")) old_ = old, had_ = true;
    if (value) setenv("SOURCE_DATE_EPOCH", value, 1);
    else unsetenv("SOURCE_DATE_EPOCH");
  }
  ~Epoch() {
    if (had_) setenv("SOURCE_DATE_EPOCH", old_.c_str(), 1);
    else unsetenv("SOURCE_DATE_EPOCH");
  }

 private:
  std::string old_;
  bool had_ = false;
};

}  // namespace

TEST_CASE("SOURCE_DATE_EPOCH dates documents when it is a whole number") {
  {
    const Epoch e("1700000000");
    REQUIRE(SourceDateEpoch().has_value());
    CHECK(*SourceDateEpoch() == 1700000000);
    CHECK(Reproducible());
    CHECK(DocumentTime() == 1700000000);
    CHECK(UtcText(DocumentTime(), "%Y-%m-%dT%H:%M:%SZ") == "2023-11-14T22:13:20Z");
  }
  for (const char* bad : {"", "12abc", "soon"}) {
    CAPTURE(bad);
    const Epoch e(bad);
    CHECK_FALSE(SourceDateEpoch().has_value());
    CHECK_FALSE(Reproducible());
  }
  const Epoch none(nullptr);
  CHECK_FALSE(Reproducible());
  CHECK(DocumentTime() > 1700000000);  // now
}

}  // namespace deb
