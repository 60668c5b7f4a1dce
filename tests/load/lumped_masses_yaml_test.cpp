// The path type lumped_masses from YAML (deb/load/lumped_masses_yaml.h):
// each rule broken once in budgets/optical_table.yaml, refused at its key.
#include "deb/load/lumped_masses_yaml.h"

#include <doctest/doctest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "deb/load/budget_yaml.h"
#include "tests/support/contains.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

using test::Contains;

std::string Text() {
  std::ifstream in(std::string(DEB_SOURCE_DIR) + "/budgets/optical_table.yaml");
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

TEST_CASE("lumped_masses: each broken rule is refused at its key") {
  const std::string text = Text();
  const auto error = [](const std::string& t) { return test::InputErrorOf([&] { LoadBudgetText(t, "b.yaml"); }); };
  struct Case {
    const char* from;
    const char* to;
    const char* says;
  };
  const Case cases[] = {
      {"between: [head, table]", "between: [head, tabel]",
       "paths[0].couplings[1].between[1]: no mass 'tabel' (did you mean 'table'?) (the masses: table, head, ground)"},
      {"between: [head, table]", "between: [head, head]", "between: the same mass twice"},
      {"between: [head, table]", "between: head", "between: name both ends, [a, b] (one may be ground)"},
      {"masses: {table: m_table, head: m_head}", "masses: {table: m_table, head: 0 kg}",
       "paths[0].masses.head: value 0 kg must be > 0"},
      {"masses: {table: m_table, head: m_head}", "masses: {table: m_table, ground: m_head}",
       "'ground' is the moving reference, not a mass"},
      {"k: k_flex, c: c_flex", "k: k_flex, c: m_head", "paths[0].couplings[1].c: 'm_head' is a quantity in kg; this value is in N.s/m"},
      {"k: k_flex, c: c_flex", "k: 0, c: 0", "a coupling needs k (N/m), c (N s/m) or both"},
      {"{name: F_ac, force: head}", "{name: F_ac, force: head, ground: acceleration}",
       "give 'force: mass' (or [mass, reaction]) or 'ground: acceleration'"},
      {"{name: F_ac, force: head}", "{name: F_ac, force: ground}", "'ground' cannot be named here: name a mass"},
      {"{name: floor_acc, ground: acceleration}", "{name: floor_acc, ground: velocity}",
       "the ground moves by its acceleration"},
      {"{name: F_ac, force: head}", "{name: F_act, force: head}", "paths[0].inputs[2].name: name 'F_act' is used twice"},
      {"input_units: [m/s^2, N, N]", "input_units: [m/s^2, N, m]", "input 'F_act' is in N: 'm' is not the same quantity"},
      {"output_unit: m\n  - name: pid", "output_unit: N\n  - name: pid", "output 'gap' is in m: 'N' is not the same quantity"},
      {"{name: gap, displacement: [head, table]}", "{name: gap, displacement: [head, table], velocity: head}",
       "give 'displacement: mass' or 'velocity: mass'"},
  };
  for (const Case& c : cases) {
    const std::string message = error(test::Replace(text, c.from, c.to));
    CHECK_MESSAGE(Contains(message, c.says), std::string(c.to) << "\n  gave: " << message);
    CHECK_MESSAGE(Contains(message, "b.yaml:"), message);
  }
}

}  // namespace deb
